#include "app/cli/session_command.h"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/cli/option_checks.h"
#include "app/cli/output_path.h"
#include "app/cli/session_repair.h"
#include "app/cli/session_summary.h"
#include "engine/core/error.h"
#include "engine/store/robomimic_io.h"
#include "engine/store/session.h"

namespace recon::cli {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

struct SessionFlags {
  std::string dir;
  bool json = false;
  std::vector<std::string> episodes;
  std::string out;
  bool include_bad = false;
  bool force = false;
  bool no_play = false;
  bool no_next_obs = false;
  bool bad = false;
  bool good = false;
  std::string split;
  double valid_fraction = 0.2;
  uint64_t seed = 1;
  std::string note;
  std::string file;
  std::vector<std::string> x_keys;
  std::string y_key;
  std::vector<std::string> beacon_keys;
};

void PrintJson(const json& value) { std::printf("%s\n", value.dump(2).c_str()); }

void RunInfo(const SessionFlags& flags) {
  const store::Session session = store::Session::Open(flags.dir, store::Session::Access::kReadOnly);
  const SessionResults results = ReadSessionResults(session);
  const json info = SessionInfoJson(session, results);
  if (flags.json) {
    PrintJson(info);
  } else {
    std::printf("%s", SessionInfoText(session, info, results).c_str());
  }
}

void RunEpisodes(const SessionFlags& flags) {
  const store::Session session = store::Session::Open(flags.dir, store::Session::Access::kReadOnly);
  if (flags.json) {
    PrintJson(EpisodesJson(session));
    return;
  }
  std::printf("%-10s %7s %8s %-6s %-5s %-4s %-20s %-22s %s\n", "episode", "samples", "teach s",
              "split", "done", "bad", "seed", "recorded", "source");
  for (const auto* list : {&session.demos(), &session.play_chunks()}) {
    for (const store::EpisodeEntry& e : *list) {
      if (!e.problem.empty()) {
        std::printf("%-10s DAMAGED: %s\n", e.name.c_str(), e.problem.c_str());
        continue;
      }
      const bool demo = e.meta.kind == "demo";
      std::printf("%-10s %7lld %8.1f %-6s %-5s %-4s %-20llu %-22s %s%s\n", e.name.c_str(),
                  static_cast<long long>(e.meta.num_samples), e.meta.teaching_seconds,
                  demo ? e.flags.split.c_str() : "-",
                  demo ? (e.meta.succeeded ? "yes" : "no") : "-", e.flags.bad ? "bad" : "",
                  static_cast<unsigned long long>(e.meta.seed), e.meta.recorded_at.c_str(),
                  e.meta.source.c_str(),
                  e.flags.note.empty() ? "" : ("  # " + e.flags.note).c_str());
    }
  }
}

void RunDelete(const SessionFlags& flags) {
  store::Session session = store::Session::Open(flags.dir);
  for (const std::string& name : flags.episodes) session.Find(name);  // all known, or nothing
  for (const std::string& name : flags.episodes) {
    session.DeleteEpisode(name);
    std::printf("moved %s to %s/trash/ (move it back into episodes/ to restore it)\n", name.c_str(),
                flags.dir.c_str());
  }
}

void RunMark(const SessionFlags& flags) {
  if (flags.bad && flags.good) throw UserError("give --bad or --good, not both");
  if (!flags.bad && !flags.good && flags.split.empty() && flags.note.empty()) {
    throw UserError("say what to mark: --bad, --good, --split train|valid or --note TEXT");
  }
  store::Session session = store::Session::Open(flags.dir);
  for (const std::string& name : flags.episodes) session.Find(name);
  for (const std::string& name : flags.episodes) {
    if (flags.bad || flags.good) session.MarkBad(name, flags.bad);
    if (!flags.split.empty()) session.SetSplit(name, flags.split);
    if (!flags.note.empty()) session.SetNote(name, flags.note);
    const store::EpisodeEntry& e = session.Find(name);
    std::printf("%s: %s, split %s%s\n", name.c_str(), e.flags.bad ? "bad" : "good",
                e.flags.split.c_str(),
                e.flags.note.empty() ? "" : (", note: " + e.flags.note).c_str());
  }
}

void RunSplit(const SessionFlags& flags) {
  store::Session session = store::Session::Open(flags.dir);
  session.AssignSplits(flags.valid_fraction, flags.seed);
  int valid = 0;
  for (const store::EpisodeEntry& e : session.demos()) valid += e.flags.split == "valid";
  std::printf("%d of %zu demonstrations for validation, the rest for training (seed %llu)\n", valid,
              session.demos().size(), static_cast<unsigned long long>(flags.seed));
}

void RunExport(const SessionFlags& flags) {
  CheckOutputFile("--out", flags.out, flags.force);
  const store::Session session = store::Session::Open(flags.dir, store::Session::Access::kReadOnly);
  store::ExportOptions options;
  options.include_bad = flags.include_bad;
  options.include_play = !flags.no_play;
  options.next_obs = !flags.no_next_obs;
  const store::ExportSummary summary = store::ExportRobomimic(session, flags.out, options);
  std::printf("wrote %s: %d demonstrations (%lld samples), %lld play samples, robomimic layout\n",
              flags.out.c_str(), summary.demos, static_cast<long long>(summary.samples),
              static_cast<long long>(summary.play_samples));
}

void RunImport(const SessionFlags& flags) {
  store::ImportMapping mapping;
  mapping.x_keys = flags.x_keys;
  mapping.y_key = flags.y_key;
  mapping.beacon_keys = flags.beacon_keys;
  const store::ImportSummary summary = store::ImportRobomimic(flags.file, flags.dir, mapping);
  std::printf(
      "imported %s into new session %s: %d demonstrations (%lld samples), %lld play "
      "samples%s\n",
      flags.file.c_str(), flags.dir.c_str(), summary.demos, static_cast<long long>(summary.samples),
      static_cast<long long>(summary.play_samples),
      summary.from_recon ? " (a RECON Studio export: manifest restored)" : "");
}

}  // namespace

void AddSessionCommands(CLI::App& app) {
  CLI::App* session = app.add_subcommand("session", "inspect and edit a teaching session");
  session->require_subcommand(1);
  const auto add = [&](const std::string& name, const std::string& help, auto run) {
    auto flags = std::make_shared<SessionFlags>();
    CLI::App* command = session->add_subcommand(name, help);
    command->callback([flags, run] { run(*flags); });
    return std::pair{command, flags};
  };

  auto [info, info_flags] = add("info", "what the session holds", RunInfo);
  info->add_option("dir", info_flags->dir, "session folder")->required();
  info->add_flag("--json", info_flags->json, "print JSON");

  auto [episodes, episodes_flags] = add("episodes", "list the episodes", RunEpisodes);
  episodes->add_option("dir", episodes_flags->dir, "session folder")->required();
  episodes->add_flag("--json", episodes_flags->json, "print JSON");

  auto [del, del_flags] =
      add("delete-episode", "move episodes to the session's trash/ folder", RunDelete);
  del->add_option("dir", del_flags->dir, "session folder")->required();
  del->add_option("episodes", del_flags->episodes, "episode names, e.g. demo_3")->required();

  auto [mark, mark_flags] =
      add("mark", "mark episodes bad or good, set their split, or note something", RunMark);
  mark->add_option("dir", mark_flags->dir, "session folder")->required();
  mark->add_option("episodes", mark_flags->episodes, "episode names, e.g. demo_3")->required();
  mark->add_flag("--bad", mark_flags->bad, "leave out of training and export");
  mark->add_flag("--good", mark_flags->good, "use again");
  mark->add_option("--split", mark_flags->split, "train or valid");
  mark->add_option("--note", mark_flags->note, "a note kept with the episode");

  auto [split, split_flags] =
      add("split", "draw train/validation masks over the demonstrations", RunSplit);
  split->add_option("dir", split_flags->dir, "session folder")->required();
  split->add_option("--valid", split_flags->valid_fraction, "fraction for validation")
      ->check(NumberBetween(0, 0.95))
      ->capture_default_str();
  split->add_option("--seed", split_flags->seed, "seed of the draw")
      ->check(SeedNumber())
      ->capture_default_str();

  auto [exp, exp_flags] = add("export", "write one robomimic HDF5 file", RunExport);
  exp->add_option("dir", exp_flags->dir, "session folder")->required();
  exp->add_option("--out", exp_flags->out, "the .hdf5 file to write")->required();
  AddForceFlag(*exp, exp_flags->force);
  exp->add_flag("--include-bad", exp_flags->include_bad, "also export bad demonstrations");
  exp->add_flag("--no-play", exp_flags->no_play, "leave play data out");
  exp->add_flag("--no-next-obs", exp_flags->no_next_obs,
                "leave robomimic's next_obs out (half the size)");

  auto [imp, imp_flags] = add("import", "make a session from a robomimic HDF5 file", RunImport);
  imp->add_option("file", imp_flags->file, "robomimic .hdf5 file")->required();
  imp->add_option("--session", imp_flags->dir, "new session folder")->required();
  imp->add_option("--x-keys", imp_flags->x_keys, "obs keys forming the robot state")
      ->delimiter(',');
  imp->add_option("--y-key", imp_flags->y_key, "obs key of the observation (image or vector)");
  imp->add_option("--beacon-keys", imp_flags->beacon_keys, "obs keys holding beacon readings")
      ->delimiter(',');

  AddSessionRepairCommand(*session);
}

}  // namespace recon::cli
