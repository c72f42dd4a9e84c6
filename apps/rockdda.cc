/**
 * @file
 * The rockdda driver: rockdda [--validate] [--print-parameters] FILE.prm
 */
#include <rockdda/io/analysis.h>

int
main(int argc, char **argv)
{
  return rockdda::io::run_driver(argc, argv);
}
