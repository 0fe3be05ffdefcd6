"""Every path of the package against the CLI of the same build on the same inputs."""

import json
import re

import numpy as np
import pytest

import pdesurf
from conftest import CLI, EXAMPLES, ROOT, cli, cli_json, read_ply

# One example of each model type.
ONE_OF_EACH = ["mug.json", "membrane.json", "vase-sections.json", "bspline-blend.json"]

# Central differences of step h against the analytic derivatives: the truncation error is
# h² |S'''| / 6 (about 1e-9 for these smooth patches of size 1-10) plus the rounding,
# 1e-16 |S| / h (about 1e-10): 1e-6 leaves orders of magnitude above both and is far below
# any real error (a wrong derivative is off by O(1)).
DERIVATIVE_STEP = 1e-5
DERIVATIVE_TOLERANCE = 1e-6
# The distance between a mesh and an identical copy, relative to its diagonal: the
# closest-point queries round to a few ulps (1e-16 measured); a vertex off by one float32 ulp
# would be 1e-8.
SAME_MESH = 1e-12


@pytest.mark.parametrize("example", EXAMPLES, ids=lambda p: p.stem)
def test_tessellation_is_the_cli_build_mesh(example, tmp_path):
    ply = tmp_path / "cli.ply"
    cli("build", example, "-o", ply, "--resolution", 9, "-q")
    positions, normals, triangles = read_ply(ply)
    mesh = pdesurf.load(example).solve().tessellate(resolution=9)
    assert mesh.positions.dtype == np.float32 and mesh.positions.shape == positions.shape
    assert mesh.vertices.dtype == np.float64 and mesh.vertices.shape == positions.shape
    assert mesh.triangles.shape == triangles.shape
    assert mesh.positions.tobytes() == positions.tobytes()  # bit for bit
    assert mesh.normals.tobytes() == normals.tobytes()
    assert (mesh.triangles == triangles).all()
    assert (mesh.vertices == positions.astype(np.float64)).all()
    assert mesh.vertex_count == len(positions) and mesh.triangle_count == len(triangles)


@pytest.mark.parametrize("name", ONE_OF_EACH)
def test_sample_is_the_cli_sample(name):
    grid = 5
    printed = cli_json("sample", ROOT / "examples" / name, "--grid", grid)["patches"]
    samples = pdesurf.load(ROOT / "examples" / name).solve().sample(grid)
    assert samples.shape == (len(printed), grid, grid, 3)
    expected = np.array([p["points"] for p in printed]).reshape(samples.shape)
    assert (samples == expected).all()  # the JSON holds doubles in shortest round-trip form


@pytest.mark.parametrize("name", ONE_OF_EACH)
def test_info_is_the_cli_info(name):
    path = ROOT / "examples" / name
    info = pdesurf.load(path).solve().info()
    printed = cli_json("info", path, "--json")
    assert info == printed
    assert list(info) == list(printed)  # the same members in the same order


@pytest.mark.parametrize("name", ONE_OF_EACH)
def test_evaluate_meets_sample_and_its_derivatives(name):
    surface = pdesurf.load(ROOT / "examples" / name).solve()
    grid = 4
    samples = surface.sample(grid)
    domains = surface.domains
    assert domains.shape == (surface.patch_count, 4)
    k, j, i = np.meshgrid(np.arange(surface.patch_count), np.arange(grid), np.arange(grid),
                          indexing="ij")
    u0, u1, v0, v1 = (domains[k, c] for c in range(4))
    # The parameters as sample computes them (the same rounding).
    u = u0 + (u1 - u0) * i / (grid - 1)
    v = v0 + (v1 - v0) * j / (grid - 1)
    points, du, dv = surface.evaluate(k, u, v)
    assert points.shape == samples.shape
    assert (points == samples).all()
    # Inside the domain, the derivatives against central differences.
    uc, vc = (u0 + u1) / 2, (v0 + v1) / 2
    h = DERIVATIVE_STEP
    _, du_c, dv_c = surface.evaluate(k, uc, vc)
    fd_u = (surface.evaluate(k, uc + h, vc)[0] - surface.evaluate(k, uc - h, vc)[0]) / (2 * h)
    fd_v = (surface.evaluate(k, uc, vc + h)[0] - surface.evaluate(k, uc, vc - h)[0]) / (2 * h)
    scale = max(1.0, np.abs(du_c).max(), np.abs(dv_c).max())
    assert np.abs(fd_u - du_c).max() < DERIVATIVE_TOLERANCE * scale
    assert np.abs(fd_v - dv_c).max() < DERIVATIVE_TOLERANCE * scale


@pytest.mark.parametrize("example", EXAMPLES, ids=lambda p: p.stem)
def test_json_round_trips(example):
    model = pdesurf.load(example)
    text = model.to_json()
    assert pdesurf.parse(text).to_json() == text
    assert pdesurf.parse(model.to_dict()).to_json() == text
    assert model.type == json.loads(example.read_text())["type"]


def test_saved_model_builds_the_same_mesh_in_the_cli(tmp_path):
    model = pdesurf.load(ROOT / "examples/vase.json")
    model.save(tmp_path / "vase.json")
    cli("build", tmp_path / "vase.json", "-o", tmp_path / "saved.ply", "-q")
    cli("build", ROOT / "examples/vase.json", "-o", tmp_path / "original.ply", "-q")
    assert (tmp_path / "saved.ply").read_bytes() == (tmp_path / "original.ply").read_bytes()


def test_vertex_frames_from_arrays_is_the_file_model():
    mug = pdesurf.load(ROOT / "examples/mug.json")
    data = mug.to_dict()
    forces = [dict(frame=k, **f) for k, frame in enumerate(data["frames"])
              for f in frame.get("forces", [])]
    rebuilt = pdesurf.vertex_frames(mug.vertices, mug.frames, mug.a1, mug.a2, forces=forces,
                                    shared_forces=data.get("forces", []), name=mug.name)
    assert rebuilt.to_json() == mug.to_json()
    a = rebuilt.solve().tessellate(9)
    b = mug.solve().tessellate(9)
    assert a.positions.tobytes() == b.positions.tobytes()


def test_a_scalar_a1_is_every_frame_and_component():
    vertices = [[0, 0, 0], [0.5, 0, 0], [1, 0, 0], [1, 0.5, 0], [1, 1, 0], [0.5, 1, 0],
                [0, 1, 0], [0, 0.5, 0]]
    flat = pdesurf.vertex_frames(vertices, [list(range(8))], a1=2.0, a2=[1, 2, 3])
    assert (flat.a1 == 2.0).all() and (flat.a2 == [[1, 2, 3]]).all()
    assert flat.solve().tessellate(5).vertices[:, 2].max() == 0.0  # a flat frame stays flat


def test_mesh_arrays_view_the_library_buffers():
    mesh = pdesurf.load(ROOT / "examples/mug.json").solve().tessellate(9)
    first, second = mesh.positions, mesh.positions
    # The same memory each time, owned by the mesh: no copy was made.
    assert first.__array_interface__["data"][0] == second.__array_interface__["data"][0]
    assert first.base is not None and not first.flags.writeable and not first.flags.owndata
    triangles = mesh.triangles
    del mesh  # the arrays keep the mesh alive
    assert triangles.max() < len(first) and np.isfinite(first).all()


@pytest.mark.parametrize("extension", ["ply", "obj", "glb"])
def test_meshes_written_by_the_cli_read_back_exactly(extension, tmp_path):
    path = tmp_path / f"mug.{extension}"
    cli("build", ROOT / "examples/mug.json", "-o", path, "--resolution", 9, "-q")
    mesh = pdesurf.read_mesh(str(path))
    ours = pdesurf.load(ROOT / "examples/mug.json").solve().tessellate(9)
    assert mesh.positions.tobytes() == ours.positions.tobytes()
    assert (mesh.triangles == ours.triangles).all()


def test_a_mesh_written_by_the_package_opens_in_the_cli(tmp_path):
    ours = pdesurf.load(ROOT / "examples/mug.json").solve().tessellate(9)
    ours.save(str(tmp_path / "mug.ply"))
    cli("build", ROOT / "examples/mug.json", "-o", tmp_path / "cli.ply", "--resolution", 9, "-q")
    assert (tmp_path / "mug.ply").read_bytes() == (tmp_path / "cli.ply").read_bytes()
    # And arrays of our own (a trimesh-style (V, F) pair) through the CLI's compare.
    pdesurf.Mesh(ours.vertices, ours.triangles).save(str(tmp_path / "pair.obj"))
    d = cli_json("compare", ROOT / "examples/mug.json", tmp_path / "pair.obj", "--resolution", 9,
                 "--json", "--samples", 2000)
    assert d["hausdorff_relative"] < SAME_MESH


def test_compare_is_the_cli_compare(tmp_path):
    reference = tmp_path / "fine.ply"
    cli("build", ROOT / "examples/vase.json", "-o", reference, "-q")
    printed = cli_json("compare", ROOT / "examples/vase.json", reference, "--resolution", 5,
                       "--samples", 5000, "--json")
    ours = pdesurf.compare(pdesurf.load(ROOT / "examples/vase.json"), str(reference),
                           resolution=5, samples=5000)
    for key in ("diagonal", "hausdorff", "hausdorff_relative"):
        assert ours[key] == printed[key]
    for way in ("model_to_mesh", "mesh_to_model"):
        assert ours[way] == printed[way]
    assert ours["model_to_mesh"]["rms"] > 0


def test_slice_is_the_cli_slice(tmp_path):
    mesh = tmp_path / "vase.ply"
    cli("build", ROOT / "examples/vase.json", "-o", mesh, "-q")
    printed = cli_json("slice", mesh, "--axis", "z", "--count", 4)
    ours = pdesurf.slice(str(mesh), axis="z", count=4)
    assert len(ours) == len(printed["planes"]) == 4
    for plane, section in zip(printed["planes"], ours):
        assert section["coordinate"] == plane["coordinate"]
        assert (section["points"] == np.array(plane["points"])).all()
        assert section["length"] == plane["length"] and section["area"] == plane["area"]


def percent(relative):
    """The CLI's "1.23%" (apps/cli/distance_report.hpp)."""
    return f"{100 * relative:.3g}%"


# Each layout: the mesh, the CLI's options, the package's keywords (two iterations: quick).
LAYOUTS = {
    "grid": ("three_peaks.off", ["--grid", 3, 3], dict(grid=(3, 3))),
    "layout": ("sphere.off", ["--layout", "cube_quad.off"], dict(layout="cube_quad.off")),
    "tube": ("elephant.off", ["--tube", 2, 5, "--axis", "y", "--range", -0.45, -0.32, "--near",
                              0.117, -0.4, -0.045],
             dict(tube=(2, 5), axis="y", range=(-0.45, -0.32), near=(0.117, -0.4, -0.045))),
}


@pytest.mark.parametrize("layout", LAYOUTS)
def test_rebuild_vertex_frames_is_the_cli_rebuild(layout, cgal_mesh, tmp_path):
    name, options, keywords = LAYOUTS[layout]
    mesh = cgal_mesh(name)
    if layout == "layout":
        keywords = dict(layout=cgal_mesh("cube_quad.off"))
        options = ["--layout", keywords["layout"]]
    out = tmp_path / "model.json"
    printed = cli("rebuild", mesh, "--as", "vertex-frames", *options, "--iterations", 2, "-o", out)
    seen = []
    model, report = pdesurf.rebuild(mesh, kind="vertex-frames", iterations=2, progress=seen.append,
                                    **keywords)
    assert model.to_json() == out.read_text()
    assert [it["iteration"] for it in seen] == [it["iteration"] for it in report["iterations"]]
    d = report["distances"]
    for label, way in (("model -> mesh", "model_to_mesh"), ("mesh -> model", "mesh_to_model")):
        w = d[way]
        line = (f"{label}  RMS {w['rms']:.6g} ({percent(w['rms_relative'])})  mean "
                f"{w['mean']:.6g} ({percent(w['mean_relative'])})  max {w['max']:.6g} "
                f"({percent(w['max_relative'])})")
        assert line in printed.splitlines()
    assert report["rms"] == (d["model_to_mesh"]["rms_relative"], d["mesh_to_model"]["rms_relative"])
    assert normals_line(report["normals"]) in printed.splitlines()
    assert f"storage        {report['storage_bytes']} bytes" in printed
    assert f"{out}: {report['stop_reason']}" in printed
    assert f"{report['frames']} frames" in printed and report["frames"] == len(model.frames)
    assert ("part" in report) == (layout == "tube")


def normals_line(normals):
    """The line `pdesurf rebuild` prints for the model's normals against the mesh's."""
    reversed_ = " (the model faces the other way, taken as it faces)" if normals["reversed"] else ""
    return (f"normals        folded {100 * normals['folded_area']:.3g}% of the model's area, "
            f"RMS deviation {normals['rms_degrees']:.3g}°{reversed_}")


def test_rebuild_fold_weight_is_the_cli_option(cgal_mesh, tmp_path):
    # fold_weight=0 (the distances alone) gives the model `--fold-weight 0` gives, and not
    # the default's: the keyword reaches the fit.
    mesh = cgal_mesh("three_peaks.off")
    out = tmp_path / "plain.json"
    cli("rebuild", mesh, "--as", "vertex-frames", "--grid", 3, 3, "--iterations", 2,
        "--fold-weight", 0, "-o", out)
    plain = pdesurf.rebuild(mesh, grid=(3, 3), iterations=2, fold_weight=0)[0]
    default = pdesurf.rebuild(mesh, grid=(3, 3), iterations=2)[0]
    assert plain.to_json() == out.read_text()
    assert default.to_json() != plain.to_json()
    with pytest.raises(ValueError, match="fold_weight"):
        pdesurf.rebuild(mesh, grid=(3, 3), iterations=2, fold_weight=-1)


def test_rebuild_normal_weight_is_the_cli_option(cgal_mesh, tmp_path):
    # normal_weight=3e-4 gives the model `--normal-weight 3e-4` gives, and not the default's
    # (off for a grid; None and 0 fit alike there): the keyword reaches the fit; a negative one
    # is refused naming it.
    mesh = cgal_mesh("three_peaks.off")
    out = tmp_path / "aligned.json"
    cli("rebuild", mesh, "--as", "vertex-frames", "--grid", 3, 3, "--iterations", 2,
        "--normal-weight", 3e-4, "-o", out)
    aligned = pdesurf.rebuild(mesh, grid=(3, 3), iterations=2, normal_weight=3e-4)[0]
    default = pdesurf.rebuild(mesh, grid=(3, 3), iterations=2)[0]
    assert aligned.to_json() == out.read_text()
    assert default.to_json() != aligned.to_json()
    off = pdesurf.rebuild(mesh, grid=(3, 3), iterations=2, normal_weight=0)[0]
    assert off.to_json() == default.to_json()
    with pytest.raises(ValueError, match="normal_weight"):
        pdesurf.rebuild(mesh, grid=(3, 3), iterations=2, normal_weight=-1)


@pytest.mark.parametrize("choice", [["--frames", 40], ["--target-rms", "0.5%"]])
def test_rebuild_automatic_layout_is_the_cli_rebuild(choice, cgal_mesh, tmp_path):
    # No layout given: the automatic layout, of about `frames` frames or the smallest reaching
    # the target RMS both ways, gives the model and the numbers `pdesurf rebuild` gives.
    mesh = cgal_mesh("sphere.off")
    out = tmp_path / "auto.json"
    printed = cli("rebuild", mesh, "--as", "vertex-frames", *choice, "--iterations", 4,
                  "-o", out)
    keywords = {"frames": choice[1]} if choice[0] == "--frames" else {"target_rms": choice[1]}
    model, report = pdesurf.rebuild(mesh, iterations=4, **keywords)
    assert model.to_json() == out.read_text()
    assert f"storage        {report['storage_bytes']} bytes" in printed
    assert f"mesh storage   {report['mesh_storage_bytes']} bytes" in printed
    assert f"{out}: {report['stop_reason']}" in printed
    assert normals_line(report["normals"]) in printed.splitlines()
    if choice[0] == "--target-rms":
        assert report["target_reached"] and report["rms_reached"]
        assert report["search_stop"] == "reached"
        assert "reached both ways" in printed
        assert max(report["rms"]) <= 0.005
        assert f"({report['trials']} layout" in printed


def test_rebuild_target_on_a_disk_may_answer_with_the_grid(cgal_mesh, tmp_path):
    # CGAL's cylinder.off is a disk (one boundary loop) that the 2 x 2 grid reaches at 0.4 %
    # within the bounds with fewer bytes than the automatic layout: the report's "grid" says
    # so, as the CLI's line does, and the model is the CLI's.
    mesh = cgal_mesh("cylinder.off")
    out = tmp_path / "grid.json"
    printed = cli("rebuild", mesh, "--as", "vertex-frames", "--target-rms", "0.4%", "-o", out)
    model, report = pdesurf.rebuild(mesh, target_rms="0.4%")
    assert model.to_json() == out.read_text()
    assert report["target_reached"]
    n = report["grid"]
    assert n > 0 and report["frames"] == n * n
    assert f"the disk's {n} × {n} grid" in printed
    # A closed mesh is no disk: no grid.
    assert pdesurf.rebuild(cgal_mesh("sphere.off"), target_rms="0.5%", iterations=4)[1]["grid"] == 0


def test_rebuild_max_normal_deviation_is_the_cli_option(cgal_mesh, tmp_path):
    # The normal bound of the target search: the keyword gives the CLI option's model, and
    # the report says which of the target's criteria the model meets.
    mesh = cgal_mesh("sphere.off")
    out = tmp_path / "auto.json"
    printed = cli("rebuild", mesh, "--as", "vertex-frames", "--target-rms", "0.5%",
                  "--max-normal-deviation", 0, "--iterations", 4, "-o", out)
    model, report = pdesurf.rebuild(mesh, iterations=4, target_rms="0.5%",
                                    max_normal_deviation=0)
    assert model.to_json() == out.read_text()
    # No smooth model deviates 0° from the sphere's facets: the RMS and fold bounds are met,
    # the normal bound is not, and the output says so.
    assert report["rms_reached"] and report["folds_reached"]
    assert not report["normals_reached"] and not report["target_reached"]
    assert report["normals"]["rms_degrees"] > 0
    # Why the search stopped: the deviation fell too little a doubling (docs/rebuild.md).
    assert report["search_stop"] == "normals stalled"
    assert "NOT the normal deviation of 0°" in printed


def test_more_frames_fit_closer(cgal_mesh):
    peaks = pdesurf.read_mesh(cgal_mesh("three_peaks.off"))
    coarse = pdesurf.rebuild(peaks.vertices, peaks.triangles, grid=(2, 2), iterations=4)[1]
    fine = pdesurf.rebuild(peaks.vertices, peaks.triangles, grid=(4, 4), iterations=4)[1]
    assert fine["rms"][0] < coarse["rms"][0] and fine["rms"][1] < coarse["rms"][1]
    assert fine["storage_bytes"] > coarse["storage_bytes"]


LEG = ["--axis", "y", "--range", -0.45, -0.32, "--count", 25, "--near", 0.117, -0.4, -0.045,
       "--name", "elephant-leg", "--samples", 5000]


def test_rebuild_cross_sections_is_the_cli_rebuild(cgal_mesh, tmp_path):
    elephant = cgal_mesh("elephant.off")
    out = tmp_path / "leg.json"
    printed = cli_json("rebuild", elephant, "--as", "cross-sections", *LEG, "-o", out, "--json")
    model, report = pdesurf.rebuild(elephant, kind="cross-sections", axis="y",
                                    range=(-0.45, -0.32), count=25, near=(0.117, -0.4, -0.045),
                                    name="elephant-leg", samples=5000)
    assert model.to_json() == out.read_text()
    assert report["storage_bytes"] == printed["model_storage_bytes"]
    assert report["part_storage_bytes"] == printed["part_storage_bytes"]
    assert report["rms"] == (printed["model_to_part"]["rms_relative"],
                             printed["part_to_model"]["rms_relative"])
    assert report["part"].triangle_count == printed["part_triangles"]
    assert len(report["sections"]) == printed["sections"]
    # Every number of the CLI's report is the package's (JSON doubles round-trip exactly).
    assert report["normals"] == printed["normals"]
    assert report["distances"]["diagonal"] == printed["diagonal"]
    for way, cli_way in (("model_to_mesh", "model_to_part"), ("mesh_to_model", "part_to_model")):
        for key, value in printed[cli_way].items():
            assert report["distances"][way][key] == value, (way, key)


def test_polygon_peer_reaches_its_target_with_the_fewest_edges(cgal_mesh):
    """The polygon peer (include/pdesurf/peers.hpp): within the target, its next coarser trial
    not; a looser target never needs more storage; target 0 is the truth itself."""
    truth = pdesurf.read_mesh(cgal_mesh("sphere.off"))
    truth_bytes = pdesurf._core.storage_bytes(truth)
    tight = pdesurf.polygon_peer(truth, 0.002, samples=5000)
    loose = pdesurf.polygon_peer(truth, "1%", samples=5000)
    for peer, target in ((tight, 0.002), (loose, 0.01)):
        assert peer["reached"] and peer["rms"] <= target < peer["coarser_rms"]
        assert peer["bytes"] == pdesurf._core.storage_bytes(peer["mesh"]) < truth_bytes
    assert loose["bytes"] <= tight["bytes"]
    exact = pdesurf.polygon_peer(truth, 0.0, samples=5000)
    assert exact["rms"] == 0.0 and exact["bytes"] == truth_bytes
    with pytest.raises(ValueError, match="target"):
        pdesurf.polygon_peer(truth, -0.1)


def test_export_is_the_cli_export(tmp_path):
    printed = cli_json("export", ROOT / "examples/mug.json", "-o", tmp_path / "cli.step", "--json")
    ours = pdesurf.export(pdesurf.load(ROOT / "examples/mug.json"), tmp_path / "mug.step")
    assert (tmp_path / "mug.step").stat().st_size > 0
    assert ours["exact_faces"] == printed["exact_faces"]
    assert ours["approximated_faces"] == printed["approximated_faces"]
    assert ours["max_deviation"] == printed["max_deviation"]
    assert ours["shells"] == printed["sewing"]["shells"]
    assert ours["free_edges"] == printed["sewing"]["free_edges"]
    iges = pdesurf.export(pdesurf.load(ROOT / "examples/mug.json").solve(), tmp_path / "mug.igs")
    assert iges["format"] == "iges" and (tmp_path / "mug.igs").stat().st_size > 0
    with pytest.raises(pdesurf.CadError):
        pdesurf.export(pdesurf.load(ROOT / "examples/mug.json"), tmp_path / "mug.dxf")


def test_session_edits_undo_and_redo():
    mug = pdesurf.load(ROOT / "examples/mug.json")
    session = pdesurf.Session(mug)
    before = session.solve().tessellate(5).positions.copy()
    moved = mug.vertices[0] + [0.0, 0.0, 0.5]
    session.apply({"op": "move-vertex", "vertex": 0, "position": moved.tolist()})
    assert (session.model.vertices[0] == moved).all() and session.undo_depth == 1
    after = session.solve().tessellate(5).positions.copy()
    assert not np.array_equal(before, after)
    assert session.undo() and (session.solve().tessellate(5).positions == before).all()
    assert session.redo() and (session.solve().tessellate(5).positions == after).all()
    assert not session.redo()
    with pytest.raises(pdesurf.ModelError) as bad:
        session.apply('{"op": "move-vertex", "vertex": 100000, "position": [0, 0, 0]}')
    assert bad.value.file == "edit" and bad.value.path.startswith("$.vertex")
    session.transform({"translate": [1, 0, 0]})
    assert (session.model.vertices[0] == moved + [1, 0, 0]).all()
    # A spectral model takes shape edits.
    shell = pdesurf.Session(pdesurf.load(ROOT / "examples/membrane.json"))
    shell.apply({"op": "set-operator", "a": 3})
    assert shell.model.to_dict()["a"] == 3 and shell.undo_depth == 1
    assert shell.undo() and shell.model.to_dict()["a"] == 2


def test_threads_setting_keeps_the_result():
    surface = pdesurf.load(ROOT / "examples/vase.json").solve()
    everything = surface.tessellate(33).positions.tobytes()
    pdesurf.set_threads(1)
    try:
        assert pdesurf.get_threads() == 1
        assert surface.tessellate(33).positions.tobytes() == everything
    finally:
        pdesurf.set_threads(0)
    assert pdesurf.get_threads() == 0


def test_model_errors_name_file_path_and_problem(tmp_path):
    bad = json.loads((ROOT / "examples/mug.json").read_text())
    bad["vertices"][1] = [0, "x", 0]
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(bad))
    with pytest.raises(pdesurf.ModelError) as error:
        pdesurf.load(path)
    e = error.value
    assert e.file == str(path) and e.path.startswith("$.vertices[1]") and e.message
    assert str(e) == f"{e.file}: {e.path}: {e.message}"
    assert isinstance(e, pdesurf.Error)
    with pytest.raises(pdesurf.ModelError) as missing:
        pdesurf.load(tmp_path / "missing.json")
    assert missing.value.file == str(tmp_path / "missing.json") and missing.value.path is None
    with pytest.raises(pdesurf.MeshIOError):
        pdesurf.read_mesh(str(tmp_path / "missing.off"))


def test_library_errors_arrive_with_the_parts_the_cpp_error_carries(tmp_path):
    # A mesh file: its name in .file, the problem alone in .message, no JSON path.
    missing = str(tmp_path / "missing.obj")
    with pytest.raises(pdesurf.MeshIOError) as read:
        pdesurf.read_mesh(missing)
    e = read.value
    assert isinstance(e, pdesurf.FileError) and isinstance(e, pdesurf.Error)
    assert e.file == missing and e.path is None
    assert e.message.startswith("cannot open: ") and str(e) == f"{missing}: {e.message}"
    # A library function's argument it cannot use: an InvalidArgumentError, a ValueError too,
    # naming no file.
    flat = pdesurf.Mesh(np.array([[0, 0, 0], [1, 0, 0], [2, 0, 0]], float),
                        np.array([[0, 1, 2]]))
    with pytest.raises(pdesurf.InvalidArgumentError) as bad:
        pdesurf.compare(pdesurf.load(ROOT / "examples/mug.json"), flat)
    assert isinstance(bad.value, ValueError)
    assert bad.value.file is None and bad.value.path is None
    assert bad.value.message and str(bad.value) == bad.value.message


def test_help_reads_well():
    for name in pdesurf.__all__:
        item = getattr(pdesurf, name)
        assert item.__doc__ and len(item.__doc__) > 20, name
    for cls in (pdesurf.Model, pdesurf.Surface, pdesurf.Mesh, pdesurf.Session):
        for member in dir(cls):
            if not member.startswith("_"):
                assert getattr(cls, member).__doc__, f"{cls.__name__}.{member}"
    assert re.search(r"resolution", pdesurf.Surface.tessellate.__doc__)
    assert (ROOT / "python/pdesurf/__init__.pyi").exists()
    assert CLI.exists()
