// `pdesurf info`: a model's counts, quality figures, bounding box and storage (the values its
// method lists, include/pdesurf/model_info.hpp), as a listing or as JSON.
#include "info_command.hpp"

#include <iostream>
#include <string>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "cli_common.hpp"
#include "commands.hpp"
#include "pdesurf/model.hpp"
#include "solve_args.hpp"

namespace pdesurf::cli {

std::string infoValueText(const nlohmann::ordered_json& value) {
  using Json = nlohmann::ordered_json;
  switch (value.type()) {
    case Json::value_t::string:
      return value.get<std::string>();
    case Json::value_t::number_unsigned:
      return fmt::format("{}", value.get<std::uint64_t>());
    case Json::value_t::number_integer:
      return fmt::format("{}", value.get<std::int64_t>());
    case Json::value_t::number_float:
      return fmt::format("{}", value.get<double>());
    case Json::value_t::boolean:
      return value.get<bool>() ? "yes" : "no";
    case Json::value_t::array: {
      std::string out = "[";
      for (std::size_t i = 0; i < value.size(); ++i)
        out += (i ? ", " : "") + infoValueText(value[i]);
      return out + "]";
    }
    default:
      if (value.is_object() && value.size() == 2 && value.contains("min") && value.contains("max"))
        return infoValueText(value["min"]) + " to " + infoValueText(value["max"]);
      return value.dump();
  }
}

std::string infoListing(const ModelInfo& info) {
  const auto line = [](std::string_view label, const std::string& text) {
    return fmt::format("{:<{}} {}\n", label, kInfoLabelWidth, text);
  };
  std::string out = line("model", info.source + (info.name.empty() ? "" : " (" + info.name + ")"));
  for (const InfoFact& fact : info.facts)
    if (!fact.label.empty())
      out += line(fact.label, fact.text.empty() ? infoValueText(fact.value) : fact.text);
  return out;
}

std::string infoJson(const ModelInfo& info) {
  nlohmann::ordered_json j = {{"model", info.source}, {"name", info.name}};
  for (const InfoFact& fact : info.facts)
    if (!fact.key.empty()) j[fact.key] = fact.value;
  // nlohmann::json keeps its members (and its records' members) in key order.
  if (info.keysSorted) return nlohmann::json::parse(j.dump()).dump(2) + "\n";
  return j.dump(2) + "\n";
}

namespace {

/// `pdesurf info`: counts, quality figures, bounding box, storage.
struct InfoCommand {
  std::string modelPath;
  bool json = false;
  SolveArgs solveArgs;

  CLI::App* add(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand(
        "info", "Counts, the largest C0 gap on shared edges, bounding box and storage size");
    addModelFile(cmd, modelPath);
    cmd->add_flag("--json", json, "print JSON");
    solveArgs.add(cmd);
    return cmd;
  }

  int run() const {
    const ModelInfo info = modelInfo(loadSolved(modelPath, solveArgs));
    std::cout << (json ? infoJson(info) : infoListing(info));
    return 0;
  }
};

}  // namespace

Registered addInfoCommand(CLI::App& app) { return registerCommand<InfoCommand>(app); }

}  // namespace pdesurf::cli
