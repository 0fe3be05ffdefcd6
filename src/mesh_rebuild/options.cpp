// The rebuild's options checked before any work, with messages in the CLI's or the Python
// package's spelling (include/pdesurf/mesh_rebuild.hpp).
#include <charconv>
#include <cmath>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "pdesurf/mesh_rebuild.hpp"

namespace pdesurf {

namespace {

/// An option's name as each front end writes it: the CLI's flag and the Python keyword (with
/// their arguments where a message shows them).
struct Spelling {
  std::string_view key, cli, python;
};

constexpr Spelling kSpellings[] = {
    {"kind", "--as", "kind"},
    {"vertex-frames", "--as vertex-frames", "kind='vertex-frames'"},
    {"layout", "--layout", "layout"},
    {"layout=", "--layout QUADS", "layout=QUADS_FILE"},
    {"grid", "--grid", "grid"},
    {"grid=", "--grid U V", "grid=(U, V)"},
    {"tube", "--tube", "tube"},
    {"tube=", "--tube RINGS SECTORS", "tube=(RINGS, SECTORS)"},
    {"frames", "--frames", "frames"},
    {"target_rms", "--target-rms", "target_rms"},
    {"quads", "--quads", "quads"},
    {"crease_angle", "--crease-angle", "crease_angle"},
    {"max_normal_deviation", "--max-normal-deviation", "max_normal_deviation"},
    {"iterations", "--iterations", "iterations"},
    {"tolerance", "--tolerance", "tolerance"},
    {"smoothness", "--smoothness", "smoothness"},
    {"fit_samples", "--fit-samples", "fit_samples"},
    {"fold_weight", "--fold-weight", "fold_weight"},
    {"normal_weight", "--normal-weight", "normal_weight"},
    {"fit_shape", "--fit-shape", "fit_shape"},
    {"resolution", "--resolution", "resolution"},
    {"count", "--count", "count"},
    {"range", "--range", "range"},
    {"near", "--near", "near"},
    {"modes", "--modes", "modes"},
    {"points", "--points", "points"},
    {"a", "--a", "a"},
    {"samples", "--samples", "samples"},
};

class Checker {
 public:
  explicit Checker(RebuildOptionStyle style) : style_(style) {}

  /// The option `key` as the style writes it.
  std::string_view operator()(std::string_view key) const {
    for (const Spelling& s : kSpellings)
      if (s.key == key) return style_ == RebuildOptionStyle::Cli ? s.cli : s.python;
    return key;
  }

  [[noreturn]] void fail(std::string_view key, const std::string& message) const {
    throw RebuildOptionError(std::string(key), message);
  }

  template <class T>
  void inRange(std::string_view key, T value, T lo, T hi) const {
    if (!(value >= lo && value <= hi))
      fail(key, fmt::format("{} {}: must be in [{}, {}]", (*this)(key), value, lo, hi));
  }

 private:
  RebuildOptionStyle style_;
};

/// A target as a fraction of the diagonal in (0, 1), `shown` as given.
void checkTarget(const Checker& name, double x, const std::string& shown) {
  if (!(x > 0.0 && x < 1.0))
    name.fail("target_rms",
              fmt::format("{} {}: the target must lie between 0 and the whole diagonal (0 and 1, "
                          "or 0% and 100%)",
                          name("target_rms"), shown));
}

void checkVertexFrames(const RebuildOptions& o, const Checker& name) {
  const int layouts = int(o.grid.has_value()) + int(o.tube.has_value()) + int(!o.quadsPath.empty());
  if (layouts > 1)
    name.fail("layout",
              fmt::format("{}: give one of {}, {} and {} (or none of them: the "
                          "automatic layout)",
                          name("vertex-frames"), name("layout="), name("grid="), name("tube=")));
  const bool automaticGiven = o.frames != 0 || o.targetRms || o.quads || o.creaseAngle.has_value();
  if (layouts == 1 && automaticGiven)
    name.fail("frames",
              fmt::format("{}, {}, {} and {} shape the automatic layout: not with {}, "
                          "{} or {}",
                          name("frames"), name("target_rms"), name("quads"), name("crease_angle"),
                          name("layout"), name("grid"), name("tube")));
  if (o.frames != 0 && o.targetRms)
    name.fail("frames", fmt::format("{} and {} both choose the number of frames: give one of them",
                                    name("frames"), name("target_rms")));
  if (o.frames != 0) name.inRange("frames", o.frames, 1u, 1000000u);
  if (o.targetRms) checkTarget(name, *o.targetRms, fmt::format("{}", *o.targetRms));
  if (o.creaseAngle) name.inRange("crease_angle", *o.creaseAngle, 0.0, 180.0);
  if (o.maxNormalDeviation) {
    if (!o.targetRms)
      name.fail("max_normal_deviation",
                fmt::format("{} bounds the search of {}: not without it",
                            name("max_normal_deviation"), name("target_rms")));
    name.inRange("max_normal_deviation", *o.maxNormalDeviation, 0.0, 180.0);
  }
  if (o.grid) {
    name.inRange("grid", (*o.grid)[0], 1u, 1000u);
    name.inRange("grid", (*o.grid)[1], 1u, 1000u);
  }
  if (o.tube) {
    name.inRange("tube", (*o.tube)[0], 1u, 1000u);
    name.inRange("tube", (*o.tube)[1], 1u, 1000u);
    if ((*o.tube)[1] < 3)
      name.fail("tube", fmt::format("{}: a tube needs at least 3 sectors round it (two would "
                                    "join along both sides)",
                                    name("tube")));
  }
  name.inRange("iterations", o.fit.maxIterations, 0u, 100000u);
  name.inRange("tolerance", o.fit.tolerance, 0.0, 1.0);
  name.inRange("smoothness", o.fit.smoothness, 0.0, 1e6);
  if (o.fit.samplesPerSide == 1 || o.fit.samplesPerSide == 2 || o.fit.samplesPerSide > 65)
    name.fail("fit_samples", fmt::format("{} {}: must be 0 (automatic) or 3 to 65",
                                         name("fit_samples"), o.fit.samplesPerSide));
  name.inRange("fold_weight", o.fit.conformalWeight, 0.0, 1.0);
  if (o.normalWeight) name.inRange("normal_weight", *o.normalWeight, 0.0, 1.0);
  if (o.fit.fitShape && o.fit.maxIterations == 0)
    name.fail("fit_shape", fmt::format("{} with {} 0 would fit nothing: the shape is fitted in "
                                       "up to {} iterations after the vertices",
                                       name("fit_shape"), name("iterations"), name("iterations")));
  name.inRange("resolution", o.resolution, 2u, 4097u);
}

void checkCrossSections(const RebuildOptions& o, const Checker& name) {
  if (o.fit.fitShape)
    name.fail("fit_shape", fmt::format("{} fits the force, a1 and a2 of vertex frames: it needs "
                                       "{}",
                                       name("fit_shape"), name("vertex-frames")));
  if (!std::isfinite(o.a) || o.a == 0.0)
    name.fail("a", fmt::format("{} {}: a must be finite and non-zero", name("a"), o.a));
  name.inRange("count", o.slice.count, 2u, 100000u);
  name.inRange("modes", o.modes, 1u, 256u);
  name.inRange("points", o.points, 8u, 100000u);
  if (o.points < 2 * o.modes + 1)
    name.fail("points",
              fmt::format("{} {} cannot determine {} {}: give at least {} points", name("points"),
                          o.points, name("modes"), o.modes, 2 * o.modes + 1));
}

}  // namespace

void checkRebuildOptions(const RebuildOptions& options, RebuildOptionStyle style) {
  const Checker name(style);
  if (options.kind == RebuildKind::VertexFrames)
    checkVertexFrames(options, name);
  else
    checkCrossSections(options, name);
  if (options.slice.range) {
    try {
      slicePlanes(options.slice, 0.0, 1.0);  // the range's own checks
    } catch (const InvalidArgument& e) {
      name.fail("range", fmt::format("{}: {}", name("range"), e.what()));
    }
  }
  if (options.slice.near && !options.slice.near->allFinite())
    name.fail("near", fmt::format("{}: {} {} {} is not a finite point", name("near"),
                                  options.slice.near->x(), options.slice.near->y(),
                                  options.slice.near->z()));
  name.inRange("samples", options.samples, std::size_t{1}, std::size_t{100000000});
}

double parseTargetRms(const std::string& text, RebuildOptionStyle style) {
  const Checker name(style);
  std::string number = text;
  const bool percentage = !number.empty() && number.back() == '%';
  if (percentage) number.pop_back();
  double x = 0.0;
  const auto [end, ec] = std::from_chars(number.data(), number.data() + number.size(), x);
  if (number.empty() || ec != std::errc() || end != number.data() + number.size())
    name.fail("target_rms",
              fmt::format("{} {}: not a number (a fraction of the diagonal such as 0.002, or a "
                          "percentage such as 0.2%)",
                          name("target_rms"), text));
  if (percentage) x /= 100.0;
  checkTarget(name, x, text);
  return x;
}

std::optional<RebuildKind> parseRebuildKind(std::string_view name) {
  if (name == "vertex-frames") return RebuildKind::VertexFrames;
  if (name == "cross-sections") return RebuildKind::CrossSections;
  return std::nullopt;
}

std::optional<QuadConstruction> parseQuadConstruction(std::string_view name) {
  if (name == "pair") return QuadConstruction::PairTriangles;
  if (name == "split") return QuadConstruction::SplitTriangles;
  return std::nullopt;
}

std::optional<ChainEnds> parseChainEnds(std::string_view name) {
  if (name == "natural") return ChainEnds::Natural;
  if (name == "estimated") return ChainEnds::Estimated;
  return std::nullopt;
}

const char* rebuildKindName(RebuildKind kind) {
  return kind == RebuildKind::VertexFrames ? "vertex-frames" : "cross-sections";
}

const char* chainEndsName(ChainEnds ends) {
  return ends == ChainEnds::Natural ? "natural" : "estimated";
}

}  // namespace pdesurf
