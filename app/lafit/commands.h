#pragma once
// lafit's subcommands. Each takes the arguments after its name and returns the exit
// code: 0 done, 1 the input could not be processed (message on stderr), 2 usage.

#include <string>
#include <vector>

namespace la::cli {

int segmentCommand(const std::vector<std::string>& args);
int fitCommand(const std::vector<std::string>& args);
int batchCommand(const std::vector<std::string>& args);
int hermiteCommand(const std::vector<std::string>& args);
int compoundCommand(const std::vector<std::string>& args);
/// `lafit alp`: one ALP curve (explicit Bezier curvature) by G1/G2 Hermite interpolation.
int alpCommand(const std::vector<std::string>& args);
/// `lafit alp-region`: the (kappa_s, kappa_e) region of monotone G2 ALP curves, as SVG and CSV.
int alpRegionCommand(const std::vector<std::string>& args);

}  // namespace la::cli
