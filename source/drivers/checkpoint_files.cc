#include <softsand/drivers/checkpoint_files.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <softsand/base/warnings.h>

#include <algorithm>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>

namespace softsand
{
  namespace drivers
  {
    using namespace dealii;

    namespace
    {
      const std::string fingerprint_tag = "scene ";
      const std::string hash_entry      = "fixed entries hash";
      const std::string pack_hash_entry = "grains/file content hash";
      /// Lines "checkpoint file NAME = BYTES" of checkpoint.info: the size
      /// of each file of the checkpoint when it was committed.
      const std::string file_size_tag = "checkpoint file ";

      /// @p value with every number written alike (15 digits), so that
      /// "1e-3" and "0.001" are the same value.
      std::string
      normalized_value(const std::string &value)
      {
        std::string out, token;
        const auto  flush = [&]() {
          if (token.empty())
            return;
          char  *end    = nullptr;
          double number = std::strtod(token.c_str(), &end);
          if (end != nullptr && *end == '\0')
            {
              char text[32];
              std::snprintf(text, sizeof(text), "%.15g", number);
              out += text;
            }
          else
            out += token;
          token.clear();
        };
        // Separators as ", " and "; ", other blanks as one space.
        for (const char c : value)
          if (c == ',' || c == ';')
            {
              flush();
              while (!out.empty() && out.back() == ' ')
                out.pop_back();
              out += c;
              out += ' ';
            }
          else if (c == ' ' || c == '\t')
            {
              flush();
              if (!out.empty() && out.back() != ' ')
                out += ' ';
            }
          else
            token += c;
        flush();
        while (!out.empty() && out.back() == ' ')
          out.pop_back();
        return out;
      }

      /// 64-bit FNV-1a of @p text, in hexadecimal: the same on every
      /// machine and compiler (std::hash is not).
      std::string
      fnv1a(const std::string &text)
      {
        std::uint64_t hash = 14695981039346656037ull;
        for (const unsigned char c : text)
          {
            hash ^= c;
            hash *= 1099511628211ull;
          }
        std::ostringstream out;
        out << std::hex << std::setw(16) << std::setfill('0') << hash;
        return out.str();
      }

      /// The number of grains of the scene as its parameters give it.
      template <int dim>
      std::string
      grain_count(const dem::GrainParameters<dim> &grains)
      {
        using Source = typename dem::GrainParameters<dim>::Source;
        switch (grains.source)
          {
            case Source::none:
              return "0";
            case Source::list:
              {
                unsigned int n = 0;
                for (const auto &item :
                     Utilities::split_string_list(grains.list, ';'))
                  if (!item.empty())
                    ++n;
                return std::to_string(n);
              }
            case Source::file:
              {
                std::ifstream in(grains.file);
                if (!in)
                  return "unknown (the pack file is unreadable)";
                unsigned int n = 0;
                for (std::string line; std::getline(in, line);)
                  {
                    const auto first = line.find_first_not_of(" \t\r");
                    if (first != std::string::npos && line[first] != '#')
                      ++n;
                  }
                return std::to_string(n);
              }
            case Source::random:
              return grains.count > 0 ? std::to_string(grains.count) :
                                        "by solid fraction";
            default:
              return "a lattice";
          }
      }

      /// A hash of the pack file's content: the grains a restart reads
      /// come from the checkpoint, so another pack under the same name
      /// would go unnoticed.
      std::string
      file_content_hash(const std::string &name)
      {
        std::ifstream in(name, std::ios::binary);
        if (!in)
          return "unknown (the pack file is unreadable)";
        std::ostringstream content;
        content << in.rdbuf();
        return fnv1a(content.str());
      }

      /// "path = value" lines as a map.
      std::map<std::string, std::string>
      entry_map(std::istream &in)
      {
        std::map<std::string, std::string> entries;
        for (std::string line; std::getline(in, line);)
          {
            const auto equals = line.find(" = ");
            if (equals != std::string::npos)
              entries[line.substr(0, equals)] = line.substr(equals + 3);
          }
        return entries;
      }

      /// Whether @p line is one of checkpoint.info's lines "TAG ENTRY =
      /// VALUE" for @p tag; if so, ENTRY -> VALUE goes into @p entries.
      bool
      read_tagged_entry(const std::string                  &line,
                        const std::string                  &tag,
                        std::map<std::string, std::string> &entries)
      {
        if (line.rfind(tag, 0) != 0)
          return false;
        const auto equals = line.find(" = ");
        if (equals != std::string::npos)
          entries[line.substr(tag.size(), equals - tag.size())] =
            line.substr(equals + 3);
        return true;
      }

      /// A value shortened for a message (a grain list may be long).
      std::string
      shortened(const std::string &value)
      {
        return value.size() <= 60 ? "<" + value + ">" :
                                    "<" + value.substr(0, 57) + "...>";
      }

      /// The fixed entries that differ between the checkpoint's file
      /// @p scene_file and @p now, but those named in @p named: "; ENTRY:
      /// <OLD> in the checkpoint, <NEW> now" each. Empty where @p scene_file
      /// is missing.
      std::string
      differing_entries(const std::string      &scene_file,
                        const std::string      &now,
                        const SceneFingerprint &named)
      {
        std::ifstream in(scene_file);
        if (!in)
          return "";
        std::istringstream now_stream(now);
        auto               old_entries = entry_map(in);
        auto               new_entries = entry_map(now_stream);
        for (const auto &[path, value] : old_entries)
          new_entries.emplace(path, "(not set)");
        std::string text;
        for (const auto &[path, value] : new_entries)
          {
            if (std::any_of(named.entries.begin(),
                            named.entries.end(),
                            [&](const auto &e) { return e.first == path; }))
              continue;
            const auto        it = old_entries.find(path);
            const std::string old_value =
              it == old_entries.end() ? "(not set)" : it->second;
            if (old_value != value)
              text += "; " + path + ": " + shortened(old_value) +
                      " in the checkpoint, " + shortened(value) + " now";
          }
        return text;
      }
    } // namespace


    namespace
    {
      /// Stop the run if a file of the checkpoint is missing or its size is
      /// not the one checkpoint.info recorded (@p sizes: name, bytes;
      /// checkpoints of earlier versions recorded none).
      void
      check_checkpoint_file_sizes(
        const std::string                        &directory,
        const std::map<std::string, std::string> &sizes)
      {
        namespace fs = std::filesystem;
        for (const auto &[name, size] : sizes)
          {
            const std::string path = directory + "/" + name;
            std::error_code   error;
            const auto        actual = fs::file_size(path, error);
            AssertThrow(!error,
                        ExcMessage("The checkpoint file <" + path +
                                   "> that " + directory +
                                   "/checkpoint.info names is missing: the "
                                   "checkpoint is incomplete. Restart from a "
                                   "complete copy of the output directory, "
                                   "or start anew (simulation control/"
                                   "restart = false)."));
            AssertThrow(std::to_string(actual) == size,
                        ExcMessage("The checkpoint file <" + path + "> has " +
                                   std::to_string(actual) + " bytes, but " +
                                   directory +
                                   "/checkpoint.info recorded " + size +
                                   " bytes when it was written: the file was "
                                   "cut short (a copy, a full disk) or "
                                   "changed. Restart from a complete copy of "
                                   "the output directory, or start anew "
                                   "(simulation control/restart = false)."));
          }
      }
    } // namespace


    template <int dim>
    std::string
    fixed_entries(const core::Parameters<dim> &parameters)
    {
      // The mesh's entries but the Kelly cycles (steady scenes only) and
      // the resolution check's override; the grains' but the overlap
      // threshold of the input check; the walls.
      const std::vector<std::string> fixed  = {"dimension",
                                               "simulation control/mode",
                                               "mesh/",
                                               "grains/",
                                               "dem/walls/"};
      const std::vector<std::string> free   = {"mesh/kelly cycles",
                                               "mesh/kelly refine fraction",
                                               "mesh/allow unresolved grains",
                                               "grains/max overlap ratio"};
      const auto                     starts = [](const std::string &path,
                             const std::string &prefix) {
        return prefix.back() == '/' ? path.rfind(prefix, 0) == 0 :
                                                          path == prefix;
      };
      std::string text;
      for (const auto &[path, value] : parameters.entries)
        if (std::any_of(fixed.begin(),
                        fixed.end(),
                        [&](const auto &p) { return starts(path, p); }) &&
            std::none_of(free.begin(), free.end(), [&](const auto &p) {
              return starts(path, p);
            }))
          text += path + " = " + normalized_value(value) + "\n";
      return text;
    }


    template <int dim>
    SceneFingerprint
    scene_fingerprint(const core::Parameters<dim> &p)
    {
      const auto entry = [&](const std::string &path) {
        const auto it = p.entries.find(path);
        return it == p.entries.end() ? std::string("(not set)") :
                                       normalized_value(it->second);
      };
      SceneFingerprint fingerprint;
      fingerprint.fixed_entries = fixed_entries(p);
      fingerprint.entries       = {
              {"simulation control/mode", entry("simulation control/mode")},
              {"dimension", std::to_string(dim)},
              {"mesh/geometry", entry("mesh/geometry")},
              {"mesh/lower corner", entry("mesh/lower corner")},
              {"mesh/upper corner", entry("mesh/upper corner")},
              {"mesh/coarse cells", entry("mesh/coarse cells")},
              {"mesh/cells per diameter", entry("mesh/cells per diameter")},
              {"mesh/mesh file", entry("mesh/mesh file")},
              {"grains/source", entry("grains/source")},
              {"grains/file", entry("grains/file")},
              {"grain count", grain_count(p.grains)}};
      if (p.grains.source == dem::GrainParameters<dim>::Source::file)
        fingerprint.entries.emplace_back(pack_hash_entry,
                                         file_content_hash(p.grains.file));
      // Last: read_checkpoint_info() names the hash as the last entry.
      fingerprint.entries.emplace_back(hash_entry,
                                       fnv1a(fingerprint.fixed_entries));
      return fingerprint;
    }


    std::string
    checkpoint_base(const std::string &directory, const unsigned long step)
    {
      return directory + "/checkpoint-" + std::to_string(step);
    }


    void
    commit_checkpoint(const std::string      &directory,
                      const unsigned long     step,
                      const std::string      &mode,
                      const SceneFingerprint &fingerprint,
                      const std::string      &info,
                      const MPI_Comm          comm)
    {
      namespace fs = std::filesystem;
      // Every rank's files are complete before the info names them.
      MPI_Barrier(comm);
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        {
          {
            std::ofstream out(checkpoint_base(directory, step) + ".scene");
            out << fingerprint.fixed_entries;
          }
          {
            std::ofstream out(directory + "/checkpoint.info.tmp");
            out << info;
            for (const auto &[entry, value] : fingerprint.entries)
              out << fingerprint_tag << entry << " = " << value << '\n';
            // Every rank's files are on disk (the barrier): their sizes let
            // a restart find a file cut short by a copy or a full disk.
            const std::string prefix = "checkpoint-" + std::to_string(step) + ".";
            std::map<std::string, std::uintmax_t> sizes;
            for (const auto &entry : fs::directory_iterator(directory))
              {
                const std::string name = entry.path().filename().string();
                if (name.rfind(prefix, 0) == 0 && entry.is_regular_file())
                  sizes[name] = entry.file_size();
              }
            for (const auto &[name, size] : sizes)
              out << file_size_tag << name << " = " << size << '\n';
            out << "mode " << mode << '\n';
          }
          fs::rename(directory + "/checkpoint.info.tmp",
                     directory + "/checkpoint.info");
          const std::string current = "checkpoint-" + std::to_string(step) + ".";
          for (const auto &entry : fs::directory_iterator(directory))
            {
              const std::string name = entry.path().filename().string();
              if (name.rfind("checkpoint-", 0) == 0 &&
                  name.rfind(current, 0) != 0)
                fs::remove(entry.path());
            }
        }
      MPI_Barrier(comm);
      // Fault injection for the restart tests: every rank dies by SIGKILL
      // (no clean-up, no flush) right after this checkpoint. Granular steps
      // take about a microsecond: no kill sent from outside lands between
      // two given checkpoints.
      if (const char *kill_step = std::getenv("SOFTSAND_SIGKILL_AFTER_CHECKPOINT"))
        if (step >= std::stoul(kill_step))
          std::raise(SIGKILL);
    }


    std::istringstream
    read_checkpoint_info(const std::string      &directory,
                         const std::string      &mode,
                         const SceneFingerprint &fingerprint,
                         const MPI_Comm          comm)
    {
      const std::string name = directory + "/checkpoint.info";
      std::ifstream     in(name);
      AssertThrow(in.good(),
                  ExcMessage("simulation control/restart = true, but there "
                             "is no checkpoint <" +
                             name +
                             ">: run with a checkpoint interval > 0 first."));
      // The scene's fingerprint apart; the rest is the scene's own.
      std::string                        text;
      std::map<std::string, std::string> written;
      std::map<std::string, std::string> file_sizes;
      for (std::string line; std::getline(in, line);)
        if (!read_tagged_entry(line, file_size_tag, file_sizes) &&
            !read_tagged_entry(line, fingerprint_tag, written))
          text += line + '\n';
      // The last line names the mode (checkpoints of earlier versions,
      // always coupled, have none).
      std::string written_by = "coupled";
      const auto  end        = text.find_last_not_of('\n');
      const auto  line_start =
        end == std::string::npos ? 0 : text.rfind('\n', end) + 1;
      if (text.compare(line_start, 5, "mode ") == 0)
        written_by = text.substr(line_start + 5, end + 1 - line_start - 5);
      AssertThrow(written_by == mode,
                  ExcMessage("simulation control/restart = true, but the "
                             "checkpoint <" +
                             name + "> was written by a " + written_by +
                             " run; this run's mode is " + mode +
                             ": restart with the parameters of that run."));

      if (written.empty())
        base::warn("The checkpoint <" + name +
                     "> was written by an earlier softsand without the "
                     "scene's fingerprint: whether it is this scene's (the "
                     "same mesh, grains and walls) cannot be checked. The "
                     "run goes on from it.",
                   comm);
      else
        {
          unsigned long step = 0;
          std::istringstream(text) >> step;
          std::string differences;
          bool        hash_differs = false;
          for (const auto &[entry, value] : fingerprint.entries)
            {
              const auto        it = written.find(entry);
              const std::string old_value =
                it == written.end() ? "(not recorded)" : it->second;
              // Checkpoints of earlier versions did not hash the pack.
              if (old_value == value ||
                  (entry == pack_hash_entry && it == written.end()))
                continue;
              if (entry == hash_entry)
                hash_differs = true;
              else
                differences += "; " + entry + ": " + shortened(old_value) +
                               " in the checkpoint, " + shortened(value) +
                               " now";
            }
          // The other fixed entries by name, from the checkpoint's copy.
          if (hash_differs)
            {
              const std::string others =
                differing_entries(checkpoint_base(directory, step) + ".scene",
                                  fingerprint.fixed_entries,
                                  fingerprint);
              if (!others.empty())
                differences += others;
              else if (differences.empty())
                differences = "; an entry of mesh/, grains/ or dem/walls/ "
                              "(their hash: <" +
                              written[hash_entry] + "> in the checkpoint, <" +
                              fingerprint.entries.back().second + "> now)";
            }
          if (!differences.empty())
            AssertThrow(false,
                        ExcMessage(
                          "simulation control/restart = true, but the "
                          "checkpoint <" +
                          name +
                          "> was written by another scene (another parameter "
                          "file's run in the same output directory, or this "
                          "one with other mesh or grain entries). What "
                          "differs: " +
                          differences.substr(2) +
                          ". Restart with the parameters of the run that "
                          "wrote it, or start anew (restart = false) in "
                          "another output directory."));
        }
      check_checkpoint_file_sizes(directory, file_sizes);
      return std::istringstream(text);
    }


    void
    check_checkpoint_info(const std::istream &info, const std::string &directory)
    {
      AssertThrow(!info.fail(),
                  ExcMessage("The checkpoint <" + directory +
                             "/checkpoint.info> is truncated or corrupt."));
    }


    std::ifstream
    open_checkpoint_file(const std::string &name)
    {
      std::ifstream in(name, std::ios::binary);
      AssertThrow(in.good(),
                  ExcMessage("The checkpoint <" + name +
                             "> is missing or unreadable."));
      return in;
    }
    template SceneFingerprint
    scene_fingerprint(const core::Parameters<2> &);
    template SceneFingerprint
    scene_fingerprint(const core::Parameters<3> &);
    template std::string
    fixed_entries(const core::Parameters<2> &);
    template std::string
    fixed_entries(const core::Parameters<3> &);
  } // namespace drivers
} // namespace softsand
