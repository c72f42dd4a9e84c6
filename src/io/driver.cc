#include <rockdda/io/analysis.h>
#include <rockdda/io/error.h>
#include <rockdda/io/parameters.h>
#include <rockdda/seismic/ground_motion.h>

#include <deal.II/base/mpi.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <sstream>

namespace rockdda::io
{
  namespace
  {
    const char *usage_text
      = "Usage: rockdda [options] FILE.prm\n"
        "\n"
        "Runs the analysis that FILE.prm describes (key 'Analysis type') and\n"
        "writes parameters.prm, statistics.csv, summary.csv and log.txt into\n"
        "its output directory.\n"
        "\n"
        "Options:\n"
        "  --validate          check FILE.prm and its input files; write "
        "nothing\n"
        "  --print-parameters  print every key with default, valid values, SI\n"
        "                      unit and help (Markdown), then exit\n"
        "  --quiet             do not echo the log to stdout\n"
        "  --help              this text\n";

    std::string
    default_output(const std::string &prm_file)
    {
      return "output-" + std::filesystem::path(prm_file).stem().string();
    }
  } // namespace



  void
  declare_all_parameters(dealii::ParameterHandler                     &prm,
                         const std::vector<std::unique_ptr<Analysis>> &analyses)
  {
    std::string names, help;
    for (const auto &a : analyses)
      {
        names += (names.empty() ? "" : "|") + a->name();
        help += " '" + a->name() + "': " + a->description() + ".";
      }
    declare(prm,
            "Analysis type",
            analyses.front()->name(),
            dealii::Patterns::Selection(names),
            "-",
            "What to compute." + help);
    declare(prm,
            "Output directory",
            "",
            dealii::Patterns::Anything(),
            "-",
            "Folder for the results, relative to the working directory. "
            "Empty: 'output-NAME' for parameter file NAME.prm.");
    seismic::GroundMotionInput::declare_parameters(prm);
    for (const auto &a : analyses)
      a->declare_parameters(prm);
  }



  bool
  started_by_mpi_launcher()
  {
    for (const char *name : {"OMPI_COMM_WORLD_SIZE",
                             "PMI_SIZE",
                             "PMI_RANK",
                             "PMIX_RANK",
                             "MPI_LOCALNRANKS",
                             "MV2_COMM_WORLD_SIZE"})
      if (std::getenv(name) != nullptr)
        return true;
    const char *force = std::getenv("ROCKDDA_MPI");
    return force != nullptr && std::string(force) == "1";
  }



  int
  run_driver(int argc, char **argv)
  {
    // With MPI, every rank runs the analysis (the heat solver distributes
    // its work); only rank 0 prints and writes files.
    const bool root
      = !dealii::Utilities::MPI::job_supports_mpi()
        || dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
    if (!root)
      std::cout.setstate(std::ios::failbit);
    bool        validate_only = false, print_parameters = false, quiet = false;
    std::string prm_file;
    for (int i = 1; i < argc; ++i)
      {
        const std::string arg = argv[i];
        if (arg == "--validate")
          validate_only = true;
        else if (arg == "--print-parameters")
          print_parameters = true;
        else if (arg == "--quiet")
          quiet = true;
        else if (arg == "--help" || arg == "-h")
          {
            std::cout << usage_text;
            return 0;
          }
        else if (!arg.empty() && arg[0] == '-')
          {
            std::cerr << "rockdda: unknown option '" << arg << "'\n\n"
                      << usage_text;
            return 2;
          }
        else if (prm_file.empty())
          prm_file = arg;
        else
          {
            std::cerr << "rockdda: only one parameter file, please ('"
                      << prm_file << "' and '" << arg << "' given)\n";
            return 2;
          }
      }

    auto                     analyses = all_analyses();
    dealii::ParameterHandler prm;
    declare_all_parameters(prm, analyses);

    if (print_parameters)
      {
        print_parameter_reference(prm, std::cout);
        return 0;
      }
    if (prm_file.empty())
      {
        std::cerr << usage_text;
        return 2;
      }

    Analysis   *analysis = nullptr;
    std::string output_path;
    try
      {
        parse_parameter_file(prm, prm_file);
        const std::string type = prm.get("Analysis type");
        for (const auto &a : analyses)
          if (a->name() == type)
            analysis = a.get();
        output_path = prm.get("Output directory");
        if (output_path.empty())
          output_path = default_output(prm_file);
        analysis->parse_parameters(prm, prm_file);
      }
    catch (const InputError &e)
      {
        if (root)
          std::cerr << "rockdda: error: " << e.what() << std::endl;
        return 1;
      }

    if (validate_only)
      {
        std::cout << prm_file << ": valid ('" << analysis->name()
                  << "' analysis)" << std::endl;
        return 0;
      }

    const auto start = std::chrono::steady_clock::now();
    Log        log(!quiet && root);
    Summary    summary;
    try
      {
        OutputDirectory output(output_path, root);
        {
          std::ostringstream resolved;
          prm.print_parameters(resolved, dealii::ParameterHandler::ShortPRM);
          output.write("parameters.prm", resolved.str());
        }
        log.line("rockdda " + analysis->name() + ": " + prm_file);
        RunContext context{output, log, summary};
        try
          {
            analysis->run(context);
          }
        catch (...)
          {
            log.line("run FAILED; see the error message");
            output.write("log.txt", log.text());
            throw;
          }
        const double seconds = std::chrono::duration<double>(
                                 std::chrono::steady_clock::now() - start)
                                 .count();
        summary.add("wall_time", seconds, "s");
        output.write("summary.csv", summary.csv());
        log.line("summary:\n" + summary.text());
        log.line("results in "
                 + std::filesystem::absolute(output.path()).string() + "/");
        output.write("log.txt", log.text());
      }
    catch (const InputError &e)
      {
        if (root)
          std::cerr << "rockdda: error: " << e.what() << std::endl;
        return 1;
      }
    catch (const std::exception &e)
      {
        if (root)
          std::cerr << "rockdda: run failed: " << e.what() << std::endl;
        return 3;
      }
    return 0;
  }
} // namespace rockdda::io
