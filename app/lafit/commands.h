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

}  // namespace la::cli
