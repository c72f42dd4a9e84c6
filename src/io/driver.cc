#include <rockdda/io/analysis.h>
#include <rockdda/io/error.h>
#include <rockdda/io/interrupt.h>
#include <rockdda/io/parameters.h>
#include <rockdda/io/provenance.h>
#include <rockdda/seismic/ground_motion.h>

#include <deal.II/base/mpi.h>

#include <chrono>
#include <csignal>
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
        "  --version           version, git commit and build type\n"
        "  --help              this text\n";

    std::string
    default_output(const std::string &prm_file)
    {
      return "output-" + std::filesystem::path(prm_file).stem().string();
    }

    /**
     * The text of parameters.prm: a comment header with the provenance of
     * the run and the SHA-256 of each input file, then every key (defaults
     * included) with the input files as absolute paths, so that the file
     * runs as it stands from any folder.
     */
    std::string
    resolved_parameters(dealii::ParameterHandler &prm,
                        const RunProvenance      &provenance,
                        const std::string        &prm_file)
    {
      std::ostringstream out;
      out << "# The fully resolved input of a rockdda run; run it again with\n"
          << "#   rockdda parameters.prm\n"
          << "# (input files by absolute path; their SHA-256 below).\n"
          << "# " << provenance.build.text() << "\n"
          << "# parameter file: "
          << std::filesystem::absolute(prm_file).lexically_normal().string()
          << "\n";
      for (const auto &[name, value] : provenance.fields())
        out << "# " << name << ": " << value << "\n";
      for (const InputFile &f : resolved_input_files())
        {
          out << "# input file '" << f.key << "' = " << f.path << "  sha256 "
              << sha256_of_file(f.path) << "\n";
          // Set the key (section path "A/B/Key") to the absolute path.
          std::vector<std::string> parts;
          std::string              rest = f.key;
          for (auto slash = rest.find('/'); slash != std::string::npos;
               slash      = rest.find('/'))
            {
                   parts.push_back(rest.substr(0, slash));
                   rest = rest.substr(slash + 1);
            }
          for (const auto &section : parts)
            prm.enter_subsection(section);
          prm.set(rest, f.path);
          for (std::size_t i = 0; i < parts.size(); ++i)
            prm.leave_subsection();
        }
      out << "\n";
      prm.print_parameters(out, dealii::ParameterHandler::ShortPRM);
      return out.str();
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
        else if (arg == "--version")
          {
            const BuildInfo b = BuildInfo::current();
            std::cout << "rockdda " << b.version << "\n"
                      << "git commit: " << b.git_commit << "\n"
                      << "build type: " << b.build_type << "\n"
                      << "deal.II: " << b.deal_ii_version << std::endl;
            return 0;
          }
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
        resolved_input_files().clear();
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
        const auto warnings = analysis->warnings();
        if (root)
          {
            for (const std::string &w : warnings)
              std::cout << prm_file << ": warning: " << w << std::endl;
            std::cout << prm_file << ": valid ('" << analysis->name()
                      << "' analysis"
                      << (warnings.empty()
                            ? std::string()
                            : ", " + std::to_string(warnings.size())
                                + " warnings")
                      << ")" << std::endl;
          }
        return 0;
      }

    const auto start = std::chrono::steady_clock::now();
    Log        log(!quiet && root);
    Summary    summary;
    try
      {
        OutputDirectory output(output_path, root);
        // The files of an earlier run into this folder go first (unless
        // this run continues it), so that no stale file (e.g. a VTU
        // snapshot beyond the new series) is mistaken for a result.
        const std::size_t removed
          = analysis->resumes() ? 0 : output.remove_earlier_run();
        const RunProvenance provenance = RunProvenance::current(argc, argv);
        output.write("parameters.prm",
                     resolved_parameters(prm, provenance, prm_file));
        log.line(provenance.build.text());
        log.line("run " + provenance.date + " on " + provenance.host + " in "
                 + provenance.working_directory + ": "
                 + provenance.command_line);
        if (removed > 0)
          log.line("removed " + std::to_string(removed)
                   + " files of an earlier run from " + output.path() + "/");
        for (const auto &[name, value] : provenance.fields())
          summary.add_text(name, value);
        log.line("rockdda " + analysis->name() + ": " + prm_file);
        RunContext context{output, log, summary, false, ""};
        // SIGINT / SIGTERM only set a flag from here on: 'dda' and 'heat'
        // stop after the current step and write what they have.
        InterruptGuard guard;
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
        const int    received = interrupt_signal_all_ranks();
        const double seconds  = std::chrono::duration<double>(
                                 std::chrono::steady_clock::now() - start)
                                 .count();
        summary.add("completed", context.stopped_early ? 0. : 1., "-");
        summary.add("wall_time", seconds, "s");
        output.write("summary.csv", summary.csv());
        log.line("summary:\n" + summary.text());
        const std::string folder
          = std::filesystem::absolute(output.path()).string() + "/";
        if (received == 0 && !context.stopped_early)
          {
            log.line("results in " + folder);
            output.write("log.txt", log.text());
            return 0;
          }
        const std::string message
          = context.stopped_early
              ? "interrupted by " + signal_name(received)
                  + "; the run stopped early and is incomplete "
                    "(summary.csv: completed = 0). "
                  + context.stopped_note + " Partial results in " + folder
              : "interrupted by " + signal_name(received)
                  + " after the analysis had finished; the results in " + folder
                  + " are complete";
        log.record(message);
        output.write("log.txt", log.text());
        if (root)
          std::cerr << "rockdda: " << message << std::endl;
        return 128 + (received != 0 ? received : SIGINT);
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
