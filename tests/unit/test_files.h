/**
 * @file
 * Helpers shared by the unit tests that write input files or expect input
 * errors: a fresh scratch folder, a file writer, and the message of the
 * InputError a call throws.
 */
#ifndef ROCKDDA_TESTS_TEST_FILES_H
#define ROCKDDA_TESTS_TEST_FILES_H

#include <rockdda/io/analysis.h>
#include <rockdda/io/error.h>

#include <deal.II/base/parameter_handler.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace rockdda::test_files
{
  /// The scratch folders of this process, removed when the test program
  /// exits (a test that fails keeps its folder only until then).
  struct ScratchFolders
  {
    std::vector<std::filesystem::path> paths;

    ~ScratchFolders()
    {
      for (const auto &p : paths)
        {
          std::error_code ignored;
          std::filesystem::remove_all(p, ignored);
        }
    }
  };

  /// A fresh, empty temporary folder for one test (unique per process),
  /// removed at exit.
  inline std::filesystem::path
  scratch(const std::string &name)
  {
    static ScratchFolders       folders;
    const std::filesystem::path p
      = std::filesystem::temp_directory_path()
        / ("rockdda-test-" + name + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(p);
    std::filesystem::create_directories(p);
    folders.paths.push_back(p);
    return p;
  }

  /// Write @p text to the file @p p.
  inline void
  write_file(const std::filesystem::path &p, const std::string &text)
  {
    std::ofstream(p) << text;
  }

  /// The contents of the file @p p ("" if it cannot be read).
  inline std::string
  read_file(const std::filesystem::path &p)
  {
    std::ifstream     in(p);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }

  /// The message of the InputError that @p f() throws ("" if none).
  template <typename F>
  std::string
  error_of(F &&f)
  {
    try
      {
        f();
      }
    catch (const InputError &e)
      {
        return e.what();
      }
    return "";
  }

  /**
   * Run analysis @p a on the parameters @p prm_text (written to
   * @p dir / "run.prm", its keys relative to the analysis's sections)
   * into the output folder @p dir / "out" (quiet); returns the summary.
   */
  inline io::Summary
  run_analysis_in(io::Analysis                &a,
                  const std::filesystem::path &dir,
                  const std::string           &prm_text)
  {
    const std::string prm_file = (dir / "run.prm").string();
    write_file(prm_file, prm_text);
    dealii::ParameterHandler prm;
    a.declare_parameters(prm);
    prm.parse_input_from_string(prm_text);
    a.parse_parameters(prm, prm_file);
    io::OutputDirectory out((dir / "out").string());
    io::Log             log(false);
    io::Summary         summary;
    io::RunContext      context{out, log, summary, false, ""};
    a.run(context);
    return summary;
  }
} // namespace rockdda::test_files

#endif
