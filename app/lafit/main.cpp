// lafit: fair curves from freehand strokes and scanned profiles, made of
// log-aesthetic curve segments. The command-line face of core/ and fitting/.

#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "app/lafit/cli_args.h"
#include "app/lafit/commands.h"

namespace {

constexpr const char* kHelp = R"(usage: lafit COMMAND [options]

Fair curves made of log-aesthetic (LA) curve segments.

commands:
  fit       fair the strokes of a point, stroke-JSON or SVG file into G2 curves
  batch     fit every input file of a folder, on all cores
  segment   one LA segment from a control triangle (3-point or inflection-end construction)
  hermite   triple-LA G2 Hermite curve between two ends (point, tangent angle, curvature)
  compound  a compound-rhythm curve: two LA segments joined G3, from four control points
  alp       one ALP curve (explicit Bezier curvature function) by G1/G2 Hermite interpolation
  alp-region  the end curvatures for which a G2 ALP curve is monotone without inflection

`lafit COMMAND --help` explains a command.
)";

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    std::cout << kHelp;
    return args.empty() ? 2 : 0;
  }
  const std::string command = args[0];
  args.erase(args.begin());
  try {
    if (command == "fit") return la::cli::fitCommand(args);
    if (command == "batch") return la::cli::batchCommand(args);
    if (command == "segment") return la::cli::segmentCommand(args);
    if (command == "hermite") return la::cli::hermiteCommand(args);
    if (command == "compound") return la::cli::compoundCommand(args);
    if (command == "alp") return la::cli::alpCommand(args);
    if (command == "alp-region") return la::cli::alpRegionCommand(args);
    std::cerr << "lafit: unknown command '" << command << "'\n" << kHelp;
    return 2;
  } catch (const la::cli::UsageError& e) {
    std::cerr << "lafit " << command << ": " << e.what() << "\n(see lafit " << command << " --help)\n";
    return 2;
  } catch (const std::exception& e) {  // unreadable files, malformed input: reported, not hidden
    std::cerr << "lafit " << command << ": " << e.what() << "\n";
    return 1;
  }
}
