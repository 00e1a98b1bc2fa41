#include "daemon/cli/cli.hpp"

int main(int argc, char** argv) { return fsd::run_cli(argc, argv); }
