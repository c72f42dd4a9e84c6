/**
 * @file
 * Provenance of a run: the build (version, git commit, build type), the run
 * (date, command line, host) and checksums of its input files, recorded in
 * log.txt, summary.csv and parameters.prm so that a result can be traced
 * to the code and the inputs that produced it.
 */
#ifndef ROCKDDA_IO_PROVENANCE_H
#define ROCKDDA_IO_PROVENANCE_H

#include <string>
#include <vector>

namespace rockdda::io
{
  /**
   * What was built: the CMake project version, the git commit of the source
   * tree when CMake configured the build ("unknown" outside a git checkout;
   * "-dirty" appended if the tree had uncommitted changes) and the CMake
   * build type. Generated at configure time (cmake/version.cc.in).
   */
  struct BuildInfo
  {
    std::string version;
    std::string git_commit;
    std::string build_type;
    std::string deal_ii_version;

    /// The build of this executable.
    static BuildInfo
    current();

    /// "rockdda 0.1.0 (commit 940e293, Release build, deal.II 9.4.2)".
    std::string
    text() const;
  };

  /**
   * One run's provenance: the build, the date and time it started (UTC, ISO
   * 8601), the command line, the host name and the working directory.
   */
  struct RunProvenance
  {
    BuildInfo   build;
    std::string date;
    std::string command_line;
    std::string host;
    std::string working_directory;

    /// The provenance of the current process started with @p argv.
    static RunProvenance
    current(const int argc, const char *const *argv);

    /// Pairs (name, value): rockdda_version, git_commit, build_type,
    /// run_date, command_line, host, working_directory.
    std::vector<std::pair<std::string, std::string>>
    fields() const;
  };

  /**
   * The SHA-256 digest (FIPS 180-4) of @p bytes as 64 lower-case hex
   * digits.
   */
  std::string
  sha256(const std::string &bytes);

  /// SHA-256 of the contents of @p file; throws InputError if unreadable.
  std::string
  sha256_of_file(const std::string &file);

  /**
   * An input file a parameter file names: the key (section path, e.g.
   * "DDA/Block file"), the value as written and the absolute path it
   * resolved to.
   */
  struct InputFile
  {
    std::string key;
    std::string value;
    std::string path;
  };

  /**
   * The input files resolved by resolve_path() since the last clear (the
   * driver clears the list before it reads a parameter file and then
   * records each file's absolute path and checksum in parameters.prm).
   */
  std::vector<InputFile> &
  resolved_input_files();
} // namespace rockdda::io

#endif
