#include "app/lafit/outputs.h"

#include <iostream>

#include "app/io/curve_export.h"
#include "core/atomic_file.h"

namespace la::cli {

namespace {

// Every drawing format from export chains (LA segments and ALP curves alike).
void writeFiles(const Args& args, const nlohmann::json& document, const std::vector<ExportCurve>& chains,
                const std::vector<std::vector<Vec2>>& points, const CurveSampling& sampling) {
  auto write = [](const std::string& path, const std::string& text) {
    writeFileAtomically(path, text);
    std::cerr << "wrote " << path << "\n";
  };
  if (auto path = args.get("-o")) write(*path, document.dump(2) + "\n");
  if (auto path = args.get("--svg")) {
    SvgOptions svg;
    svg.show_comb = args.has("--comb");
    svg.y_up = args.has("--y-up");
    write(*path, exportCurvesToSvg(chains, points, svg));
  }
  if (auto path = args.get("--csv")) write(*path, exportCurvesToCsv(chains, sampling));
  if (auto path = args.get("--dxf")) write(*path, exportCurvesToDxf(chains));
}

}  // namespace

std::optional<Args> producingCommandArgs(const std::vector<std::string>& argv, const std::set<std::string>& valued,
                                         const std::set<std::string>& flags, const char* help) {
  std::set<std::string> all_valued = kOutputOptions, all_flags = kOutputFlags;
  all_valued.insert(valued.begin(), valued.end());
  all_flags.insert(flags.begin(), flags.end());
  all_flags.insert("--help");
  Args args(argv, all_valued, all_flags);
  if (!args.has("--help")) return args;
  std::cout << help;
  return std::nullopt;
}

void writeOutputs(const Args& args, const nlohmann::json& document, const std::vector<Curve>& curves,
                  const std::vector<std::vector<Vec2>>& points) {
  std::vector<LaSegmentView> views;
  writeFiles(args, document, exportChains(curves, views), points, CurveSampling{});
}

void writeAlpOutputs(const Args& args, const nlohmann::json& document, const std::vector<AlpCurve>& curves,
                     const std::vector<std::vector<Vec2>>& points, int csv_samples) {
  writeFiles(args, document, exportChains(curves), points, CurveSampling{csv_samples});
}

}  // namespace la::cli
