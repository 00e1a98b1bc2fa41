#pragma once
// The `fsd` command line (DESIGN.md §9). Exit status: 0 success, 1 mission failed, 2 bad usage or input.
namespace fsd {

enum ExitCode : int { kExitOk = 0, kExitMissionFailed = 1, kExitBadInput = 2 };

int run_cli(int argc, char** argv);

}  // namespace fsd
