#include "app/lafit/outputs.h"

#include <iostream>

#include "app/io/curve_export.h"
#include "core/atomic_file.h"

namespace la::cli {

void writeOutputs(const Args& args, const nlohmann::json& document, const std::vector<Curve>& curves,
                  const std::vector<std::vector<Vec2>>& points) {
  if (auto path = args.get("-o")) {
    writeFileAtomically(*path, document.dump(2) + "\n");
    std::cerr << "wrote " << *path << "\n";
  }
  if (auto path = args.get("--svg")) {
    SvgOptions svg;
    svg.show_comb = args.has("--comb");
    svg.y_up = args.has("--y-up");
    writeFileAtomically(*path, curvesToSvg(curves, points, svg));
    std::cerr << "wrote " << *path << "\n";
  }
  if (auto path = args.get("--csv")) {
    writeFileAtomically(*path, curvesToCsv(curves));
    std::cerr << "wrote " << *path << "\n";
  }
  if (auto path = args.get("--dxf")) {
    writeFileAtomically(*path, curvesToDxf(curves));
    std::cerr << "wrote " << *path << "\n";
  }
}

void writeAlpOutputs(const Args& args, const nlohmann::json& document, const std::vector<AlpCurve>& curves,
                     const std::vector<std::vector<Vec2>>& points, int csv_samples) {
  if (auto path = args.get("-o")) {
    writeFileAtomically(*path, document.dump(2) + "\n");
    std::cerr << "wrote " << *path << "\n";
  }
  if (auto path = args.get("--svg")) {
    SvgOptions svg;
    svg.show_comb = args.has("--comb");
    svg.y_up = args.has("--y-up");
    writeFileAtomically(*path, alpCurvesToSvg(curves, points, svg));
    std::cerr << "wrote " << *path << "\n";
  }
  if (auto path = args.get("--csv")) {
    writeFileAtomically(*path, alpCurvesToCsv(curves, CurveSampling{csv_samples}));
    std::cerr << "wrote " << *path << "\n";
  }
  if (auto path = args.get("--dxf")) {
    writeFileAtomically(*path, alpCurvesToDxf(curves));
    std::cerr << "wrote " << *path << "\n";
  }
}

}  // namespace la::cli
