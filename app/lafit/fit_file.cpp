#include "app/lafit/fit_file.h"

#include <atomic>
#include <exception>
#include <mutex>
#include <thread>

#include <new>

#include "app/io/fit_json.h"
#include "app/io/fit_options_json.h"
#include "app/io/point_file.h"
#include "core/curve_json.h"

namespace la::cli {

std::vector<Curve> FileFit::curves() const {
  std::vector<Curve> out;
  for (const auto& r : results)
    if (r) out.push_back(r->curve);
  return out;
}

std::vector<std::vector<Vec2>> FileFit::points() const {
  std::vector<std::vector<Vec2>> out;
  for (std::size_t i = 0; i < strokes.size(); ++i) {
    if (results[i]) {
      out.push_back(results[i]->cleaned.points);
    } else {
      std::vector<Vec2> raw;
      for (const StrokeSample& s : strokes[i].samples) raw.push_back(s.p);
      out.push_back(raw);
    }
  }
  return out;
}

int FileFit::failed() const {
  int n = 0;
  for (const auto& e : errors) n += !e.empty();
  return n;
}

FileFit fitFile(const std::filesystem::path& input, const FitOptions& options, const ReadLimits& limits,
                bool with_stages, int jobs) {
  FileFit out;
  out.strokes = readStrokes(input, limits);
  const std::size_t n = out.strokes.size();
  std::vector<nlohmann::json> entries(n);
  out.results.resize(n);
  out.errors.resize(n);
  auto fitOne = [&](std::size_t i) {
    const std::string where = input.string() + ": stroke " + std::to_string(i + 1) + ": ";
    try {
      FitResult r = fitStroke(out.strokes[i], options);
      entries[i] = fitResultToJson(r, out.strokes[i], with_stages);
      out.results[i] = std::move(r);
      return;
    } catch (const StrokeError& e) {  // a dot, a straight tap: this stroke only
      out.errors[i] = where + e.what();
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const std::exception& e) {
      // A stage refusing what the clean-up let through (a closed stroke of 3 points did,
      // until the clean-up refused it): still this stroke only, and the message must
      // say which file and stroke, which the stage's own words do not.
      out.errors[i] = where + "stroke cannot be fitted: " + e.what();
    }
    entries[i] = {{"error", out.errors[i]}};
  };
  // The strokes of one file are independent: fitted on `jobs` threads, each taking the
  // next stroke, results in file order. (An exception other than a stroke's own, out of
  // memory, ends the file: the first one is rethrown after the threads stop.)
  std::atomic<std::size_t> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto worker = [&] {
    for (std::size_t i; (i = next++) < n;) {
      try {
        fitOne(i);
      } catch (...) {
        const std::lock_guard lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        next = n;
      }
    }
  };
  std::vector<std::thread> pool;
  for (int j = 1; j < std::min<int>(jobs, static_cast<int>(n)); ++j) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  nlohmann::json curves = nlohmann::json::array();
  for (nlohmann::json& entry : entries) curves.push_back(std::move(entry));
  out.document = curves.size() == 1 && !curves[0].contains("error") ? curves[0] : nlohmann::json{{"curves", curves}};
  out.document["options"] = fitOptionsToJson(options);
  stampCurvesFormat(out.document);
  return out;
}

}  // namespace la::cli
