// forensim: the command-line program's entry point (the command line itself is cli_main.cpp).

#include "cli_main.hpp"

int main(int argc, char** argv) {
  return forensim::cli::run_main(argc, argv);
}
