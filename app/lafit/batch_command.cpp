// `lafit batch`: every input file of a folder, on all cores, with a progress bar and a
// summary table. A file that cannot be read or fitted is reported and skipped.

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <mutex>
#include <thread>

#include "app/lafit/commands.h"
#include "app/lafit/fit_file.h"
#include "app/lafit/fit_options.h"
#include "app/io/curve_export.h"
#include "core/atomic_file.h"

namespace la::cli {
namespace {

namespace fs = std::filesystem;

constexpr const char* kHelp = R"(usage: lafit batch DIR -o OUTDIR [options]

Fits every input file in DIR (.csv .txt .dat .json .svg; with --recursive also in its
subfolders, leaving out OUTDIR if it is one) and writes OUTDIR/<name>.json for each,
keeping the folder structure. Inputs that differ only in their extension (a.csv and
a.json) keep it in their output's name (a.csv.json, a.json.json). OUTDIR must not be
DIR itself.

  -o OUTDIR       output folder (created if missing)
  --recursive     descend into subfolders
  --svg           also write OUTDIR/<name>.svg
  --jobs N        parallel jobs (default: all cores)

A file that cannot be read is reported in the summary and skipped; the others are
still fitted and written. A file none of whose strokes can be fitted gets no output, as
with `lafit fit` (an existing one is left as it was). The summary counts files and
strokes.

exit status: 0 every file and stroke fitted, 1 some file could not be read or some
stroke could not be fitted (the summary says which), 2 usage error

)";

bool isInput(const fs::path& p) {
  const std::string ext = p.extension().string();
  return ext == ".csv" || ext == ".txt" || ext == ".dat" || ext == ".json" || ext == ".svg";
}

struct Row {
  std::string name;
  int strokes = 0, failed = 0, segments = 0;
  double max_dev_rel = 0.0, g2_gap = 0.0, ms = 0.0;
  std::string error;
};

}  // namespace

int batchCommand(const std::vector<std::string>& argv) {
  std::set<std::string> valued = {"-o", "--jobs"}, flags = {"--recursive", "--svg", "--help"};
  valued.insert(kFitValued.begin(), kFitValued.end());
  flags.insert(kFitFlags.begin(), kFitFlags.end());
  const Args args(argv, valued, flags);
  if (args.has("--help")) {
    std::cout << kHelp << kFitOptionsHelp;
    return 0;
  }
  if (args.positional().size() != 1) throw UsageError("batch needs exactly one input folder");
  const auto out_dir = args.get("-o");
  if (!out_dir) throw UsageError("batch needs -o OUTDIR");
  const fs::path in_dir = args.positional()[0];
  if (!fs::is_directory(in_dir)) throw std::runtime_error(in_dir.string() + ": not a folder");
  const FitOptions options = fitOptionsFrom(args);
  const ReadLimits limits = readLimitsFrom(args);

  // OUTDIR beside the inputs would mix the curves with them (a run after would read them
  // back); inside DIR it is left out of the scan.
  const fs::path in_abs = fs::weakly_canonical(in_dir), out_abs = fs::weakly_canonical(*out_dir);
  if (in_abs == out_abs) throw UsageError("-o OUTDIR must not be the input folder itself");
  auto inOutDir = [&](const fs::path& p) {
    const fs::path rel = fs::weakly_canonical(p).lexically_relative(out_abs);
    return !rel.empty() && *rel.begin() != "..";
  };
  std::vector<fs::path> files;
  if (args.has("--recursive")) {
    for (auto it = fs::recursive_directory_iterator(in_dir); it != fs::recursive_directory_iterator(); ++it) {
      if (it->is_directory() && fs::weakly_canonical(it->path()) == out_abs) it.disable_recursion_pending();
      else if (it->is_regular_file() && isInput(it->path()) && !inOutDir(it->path())) files.push_back(it->path());
    }
  } else {
    for (const auto& e : fs::directory_iterator(in_dir))
      if (e.is_regular_file() && isInput(e.path())) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) throw std::runtime_error(in_dir.string() + ": no input files (.csv .txt .dat .json .svg)");
  // Each input's curves go to OUTDIR/<its path>.json; inputs that would share one (a.csv
  // and a.json) keep their extension in it (a.csv.json, a.json.json).
  std::map<fs::path, int> users;
  for (const fs::path& f : files) ++users[fs::relative(f, in_dir).replace_extension()];
  auto outputOf = [&](const fs::path& file, const char* extension) {
    fs::path rel = fs::relative(file, in_dir);
    if (users[fs::path(rel).replace_extension()] > 1) rel += extension;
    else rel.replace_extension(extension);
    return fs::path(*out_dir) / rel;
  };

  std::vector<Row> rows(files.size());
  std::atomic<std::size_t> next{0}, done{0};
  std::mutex print;
  const int jobs = std::max(1, args.integer("--jobs", static_cast<int>(std::max(1u, std::thread::hardware_concurrency()))));
  auto worker = [&] {
    for (std::size_t i; (i = next++) < files.size();) {
      Row& row = rows[i];
      const fs::path rel = fs::relative(files[i], in_dir);
      row.name = rel.string();
      try {
        const auto t0 = std::chrono::steady_clock::now();
        const FileFit fit = fitFile(files[i], options, limits, args.has("--stages"));
        row.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        row.strokes = static_cast<int>(fit.strokes.size());
        row.failed = fit.failed();
        if (row.failed < row.strokes) {  // (as `lafit fit`: nothing written where no stroke fits)
          const fs::path target = outputOf(files[i], ".json");
          fs::create_directories(target.parent_path());
          writeFileAtomically(target, fit.document.dump(2) + "\n");
          if (args.has("--svg")) writeFileAtomically(outputOf(files[i], ".svg"), curvesToSvg(fit.curves(), fit.points()));
        }
        for (const auto& r : fit.results) {
          if (!r) continue;
          row.segments += r->quality.segments;
          row.max_dev_rel = std::max(row.max_dev_rel, r->quality.max_dev / std::max(r->quality.diagonal, 1e-300));
          row.g2_gap = std::max(row.g2_gap, r->quality.g2_gap);
        }
        if (row.failed) row.error = fit.errors[std::find_if(fit.errors.begin(), fit.errors.end(), [](const std::string& e) { return !e.empty(); }) - fit.errors.begin()];
      } catch (const std::exception& e) {
        row.error = e.what();
      }
      const std::size_t k = ++done;
      std::lock_guard lock(print);
      const int width = 40, filled = static_cast<int>(width * k / files.size());
      std::fprintf(stderr, "\r[%s%s] %zu/%zu", std::string(filled, '#').c_str(), std::string(width - filled, ' ').c_str(), k,
                   files.size());
      std::fflush(stderr);
    }
  };
  std::vector<std::thread> pool;
  for (int j = 0; j < jobs; ++j) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  std::fprintf(stderr, "\n");

  std::printf("%-50s %7s %6s %8s %12s %9s %9s\n", "file", "strokes", "failed", "segments", "max_dev/diag", "g2_gap", "time_ms");
  int bad_files = 0, bad_strokes = 0, strokes = 0, unwritten = 0;
  for (const Row& r : rows) {
    if (r.strokes == 0 && !r.error.empty()) {
      ++bad_files;
      std::printf("%-50s error: %s\n", r.name.c_str(), r.error.c_str());
      continue;
    }
    strokes += r.strokes;
    bad_strokes += r.failed;
    if (r.failed == r.strokes) ++unwritten;
    std::printf("%-50s %7d %6d %8d %12.3g %9.2g %9.2f\n", r.name.c_str(), r.strokes, r.failed, r.segments, r.max_dev_rel,
                r.g2_gap, r.ms);
  }
  std::printf("%zu files: %zu fitted, %d unreadable, %d without a stroke that fits (not written); "
              "%d strokes: %d fitted, %d could not be fitted\n",
              files.size(), files.size() - bad_files - unwritten, bad_files, unwritten, strokes, strokes - bad_strokes,
              bad_strokes);
  return (bad_files || bad_strokes) ? 1 : 0;
}

}  // namespace la::cli
