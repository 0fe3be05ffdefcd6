#include "export_command.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "pdesurf/cad_export.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/nurbs.hpp"

namespace pdesurf::cli {

namespace {

using Json = nlohmann::ordered_json;

/// A well-formed argument that cannot be used (exit 2).
struct ExportUsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Converted {
  std::string name;
  NurbsModel nurbs;
  double solveMs = 0.0, convertMs = 0.0;
};

Converted convert(const std::string& path, const NurbsExportOptions& options) {
  AnyModel any = loadModel(path);
  Converted out;
  auto t0 = Clock::now();
  const SolvedModel solved = solve(std::move(any), path);
  out.solveMs = msSince(t0);
  out.name = solved.displayName();
  t0 = Clock::now();
  out.nurbs = toNurbs(solved, options);
  out.convertMs = msSince(t0);
  return out;
}

}  // namespace

CLI::App* ExportCommand::add(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "export",
      "Write a model's patches as B-spline faces, sewn into shells, to STEP or IGES (chosen by "
      "the output's extension): exact where a patch is polynomial, within --tolerance otherwise");
  addModelFile(cmd, modelPath);
  cmd->add_option("-o,--output", outPath, "file to write: .step .stp .igs .iges")->required();
  toleranceOption = cmd->add_option(
      "--tolerance", tolerance,
      "largest deviation of an approximated face from its patch, in model units (default: "
      "1e-4 of the model's bounding-box diagonal); also the sewing tolerance. Given, a face "
      "that cannot meet it is an error; by default such a face is written as the finest fit "
      "tried, with a warning naming its deviation");
  cmd->add_option("--max-spans", maxSpans,
                  "refinement cap of an approximated face, knot spans per direction")
      ->capture_default_str()
      ->check(CLI::Range(4u, 4096u));
  cmd->add_flag("--json", json, "print the report as JSON");
  cmd->add_flag("-q,--quiet", quiet, "print nothing on success");
  return cmd;
}

int ExportCommand::run() const {
  try {
    NurbsExportOptions options;
    if (toleranceOption && toleranceOption->count() > 0) {
      if (!std::isfinite(tolerance) || tolerance <= 0.0)
        throw ExportUsageError(
            fmt::format("--tolerance {}: must be a positive, finite distance", tolerance));
      options.tolerance = tolerance;
    } else {
      options.keepBest = true;  // the default tolerance is a goal, not a promise asked for
    }
    options.maxSpans = maxSpans;
    CadFormat format;
    try {
      format = cadFormatFromPath(outPath);
    } catch (const CadError& e) {
      throw ExportUsageError(e.what());
    }
    Converted model;
    try {
      model = convert(modelPath, options);
    } catch (const NurbsToleranceError& e) {
      throw ExportUsageError(fmt::format("{}: {}", modelPath, e.what()));
    }
    const NurbsModel& nurbs = model.nurbs;
    const auto t0 = Clock::now();
    const CadExportReport report = writeCad(nurbs, outPath, format);
    const double writeMs = msSince(t0);
    const double deviation = nurbs.maxDeviation();
    const double relative = nurbs.diagonal > 0.0 ? deviation / nurbs.diagonal : deviation;
    // After the report: the warning is the last thing a user reads.
    const auto warnOverTolerance = [&] {
      const std::size_t over = nurbs.overToleranceCount();
      if (over == 0) return;
      std::fflush(stdout);
      fmt::print(stderr,
                 "pdesurf: warning: {}: {} of {} missed the tolerance {:.3g} within {} spans per "
                 "direction and {} written as the finest fit tried: max deviation {:.3g} ({:.2g} "
                 "of the bounding-box diagonal); give a larger --tolerance or --max-spans\n",
                 outPath, count(over, "face"), nurbs.faces.size(), nurbs.tolerance, maxSpans,
                 over == 1 ? "is" : "are", deviation, relative);
    };
    if (quiet) {
      warnOverTolerance();
      return 0;
    }
    const std::size_t exact = nurbs.exactCount();
    if (json) {
      Json faces = Json::array();
      for (const NurbsFace& f : nurbs.faces)
        faces.push_back({{"patch", f.patch},
                         {"exact", f.exact},
                         {"deviation", f.deviation},
                         {"within_tolerance", f.withinTolerance},
                         {"poles", {f.surface.uCount, f.surface.vCount}}});
      const Json j = {{"model", modelPath},
                      {"output", outPath},
                      {"format", format == CadFormat::Step ? "step" : "iges"},
                      {"exact_faces", exact},
                      {"approximated_faces", nurbs.faces.size() - exact},
                      {"tolerance", nurbs.tolerance},
                      {"diagonal", nurbs.diagonal},
                      {"max_deviation", deviation},
                      {"max_deviation_relative", relative},
                      {"faces_over_tolerance", nurbs.overToleranceCount()},
                      {"sewing",
                       {{"tolerance", report.sewingTolerance},
                        {"shells", report.shells},
                        {"free_edges", report.freeEdges},
                        {"multiple_edges", report.multipleEdges},
                        {"degenerated_edges", report.degeneratedEdges}}},
                      {"faces", std::move(faces)}};
      std::cout << j.dump(2) << '\n';
      std::cout.flush();
      warnOverTolerance();
      return 0;
    }
    fmt::print(
        "{}: {} ({} exact, {} approximated), max deviation {:.2g} ({:.2g} of the bounding-box "
        "diagonal), tolerance {:.3g} -> {} (solve {:.3f} ms, convert {:.3f} ms, write {:.1f} "
        "ms)\n",
        model.name, count(nurbs.faces.size(), "face"), exact, nurbs.faces.size() - exact, deviation,
        relative, nurbs.tolerance, outPath, model.solveMs, model.convertMs, writeMs);
    fmt::print("sewn: {}, {}, {}{}\n", count(report.shells, "shell"),
               count(report.freeEdges, "free edge"),
               count(report.degeneratedEdges, "degenerated edge"),
               report.multipleEdges ? ", " + count(report.multipleEdges, "multiple edge") : "");
    warnOverTolerance();
    return 0;
  } catch (const ExportUsageError& e) {
    fmt::print(stderr, "pdesurf: {}\n", e.what());
    return kExitUsage;
  }
}

}  // namespace pdesurf::cli
