#include "app/lafit/fit_file.h"

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

FileFit fitFile(const std::filesystem::path& input, const FitOptions& options, bool with_stages) {
  FileFit out;
  out.strokes = readStrokes(input);
  nlohmann::json curves = nlohmann::json::array();
  for (std::size_t i = 0; i < out.strokes.size(); ++i) {
    const std::string where = input.string() + ": stroke " + std::to_string(i + 1) + ": ";
    std::string why;
    try {
      FitResult r = fitStroke(out.strokes[i], options);
      curves.push_back(fitResultToJson(r, out.strokes[i], with_stages));
      out.results.push_back(std::move(r));
      out.errors.emplace_back();
      continue;
    } catch (const StrokeError& e) {  // a dot, a straight tap: this stroke only
      why = where + e.what();
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const std::exception& e) {
      // A stage refusing what the clean-up let through (a closed stroke of 3 points did,
      // until the clean-up refused it): still this stroke only, and the message must
      // say which file and stroke, which the stage's own words do not.
      why = where + "stroke cannot be fitted: " + e.what();
    }
    curves.push_back({{"error", why}});
    out.results.emplace_back();
    out.errors.push_back(why);
  }
  out.document = curves.size() == 1 && !curves[0].contains("error") ? curves[0] : nlohmann::json{{"curves", curves}};
  out.document["options"] = fitOptionsToJson(options);
  stampCurvesFormat(out.document);
  return out;
}

}  // namespace la::cli
