// Sub-commands of the `evas` executable. Each takes the arguments after its
// name (args[0] is the sub-command) and returns the process exit code:
// 0 success, 1 bad input (InputError), 2 the run or the command failed.
#pragma once

#include <string>
#include <vector>

namespace evas::cli {

int cmd_run(const std::vector<std::string>& args);
int cmd_info(const std::vector<std::string>& args);
int cmd_export(const std::vector<std::string>& args);
int cmd_body(const std::vector<std::string>& args);
int cmd_elements(const std::vector<std::string>& args);
int cmd_modal(const std::vector<std::string>& args);

}  // namespace evas::cli
