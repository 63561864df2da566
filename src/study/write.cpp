#include "imunoise/study/write.hpp"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <fmt/core.h>

#include "imunoise/error.hpp"
#include "imunoise/study/render.hpp"

namespace imunoise::study {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw InputError(path.string() + ": cannot create the file; check the directory");
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!out) throw InputError(path.string() + ": write failed (disk full?)");
}

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// Removes the staging directory however write_report leaves.
struct Staging {
  fs::path path;
  ~Staging() {
    std::error_code ec;
    if (!path.empty()) fs::remove_all(path, ec);
  }
};

}  // namespace

std::string find_plotly_js() {
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("IMUNOISE_PLOTLY_JS"); env != nullptr && *env != '\0') {
    candidates.emplace_back(env);
  }
#ifdef IMUNOISE_SOURCE_DIR
  candidates.emplace_back(std::string(IMUNOISE_SOURCE_DIR) +
                          "/web/node_modules/plotly.js-basic-dist-min/plotly-basic.min.js");
#endif
#ifdef IMUNOISE_INSTALL_DATADIR
  candidates.emplace_back(std::string(IMUNOISE_INSTALL_DATADIR) + "/plotly-basic.min.js");
#endif
  for (const auto& c : candidates) {
    std::error_code ec;
    if (fs::is_regular_file(c, ec)) return c;
  }
  return {};
}

void check_report_dir(const std::string& dir, bool force) {
  const fs::path root(dir);
  std::error_code ec;
  if (fs::exists(root, ec) && !fs::is_directory(root, ec)) {
    throw InputError(dir + ": exists and is not a directory; fix: choose another -o DIR");
  }
  if (force) return;
  for (const char* name : {"report.json", "report.html", "report.md"}) {
    if (fs::exists(root / name, ec)) {
      throw InputError(dir + ": already holds " + name + "; imunoise does not overwrite a report — "
                       "choose another -o DIR or pass --force");
    }
  }
}

WrittenReport write_report_files(std::map<std::string, std::string> texts, const HtmlRenderer& html,
                                 const nlohmann::json& figures_doc, const std::string& dir,
                                 const WriteOptions& options) {
  WrittenReport written;
  written.dir = dir;
  const fs::path root(dir);
  std::error_code ec;
  if (fs::exists(root, ec) && !fs::is_directory(root, ec)) {
    throw InputError(dir + ": exists and is not a directory; fix: choose another -o DIR");
  }
  fs::create_directories(root, ec);
  if (ec) {
    throw InputError(dir + ": cannot create the report directory (" + ec.message() +
                     "); fix: choose a writable -o DIR");
  }
  if (::access(root.c_str(), W_OK | X_OK) != 0) {
    throw InputError(dir + ": the directory is not writable; fix: choose a writable -o DIR or "
                     "change its permissions");
  }
  std::string plotly_path = options.plotly_js_path.empty() ? find_plotly_js()
                                                           : options.plotly_js_path;
  std::string plotly;
  if (!plotly_path.empty()) {
    plotly = slurp(plotly_path);
    if (plotly.empty()) {
      throw InputError(plotly_path + ": Plotly.js is empty or unreadable; fix: run npm ci in "
                       "web/ or point IMUNOISE_PLOTLY_JS at plotly-basic.min.js");
    }
  } else {
    written.notes.push_back(
        "report.html shows the static SVG figures: Plotly.js was not found (run `npm ci` in the "
        "repository's web/ folder, or set IMUNOISE_PLOTLY_JS)");
  }
  written.interactive = !plotly.empty();
  texts["report.html"] = html(plotly);
  std::vector<std::string> figure_files;
  const bool figures = !options.gnuplot.empty();
  if (figures) {
    for (const auto& f : figures_doc) {
      const std::string stem = file_stem(f["id"].get<std::string>());
      figure_files.push_back("figures/" + stem + ".svg");
      figure_files.push_back("figures/" + stem + ".png");
    }
  }
  // Refuse before writing anything.
  if (!options.force) {
    std::vector<std::string> existing;
    for (const auto& [name, text] : texts) {
      if (fs::exists(root / name, ec)) existing.push_back(name);
    }
    for (const auto& name : figure_files) {
      if (fs::exists(root / name, ec)) existing.push_back(name);
    }
    if (!existing.empty()) {
      throw InputError(fmt::format(
          "{}: already holds {}{}; imunoise does not overwrite a report — choose another -o DIR "
          "or pass --force",
          dir, existing.front(),
          existing.size() > 1 ? fmt::format(" and {} more report files", existing.size() - 1)
                              : std::string()));
    }
  }
  Staging staging;
  staging.path = root / fmt::format(".imunoise-staging-{}", ::getpid());
  fs::remove_all(staging.path, ec);
  fs::create_directories(staging.path / "figures", ec);
  if (ec) {
    throw InputError(dir + ": cannot write into the directory (" + ec.message() +
                     "); fix: choose a writable -o DIR");
  }
  for (const auto& [name, text] : texts) write_file(staging.path / name, text);
  if (figures) {
    std::string script;
    for (const auto& f : figures_doc) {
      const std::string stem = file_stem(f["id"].get<std::string>());
      script += "reset\n" + gnuplot_script(f, (staging.path / "figures" / (stem + ".svg")).string(),
                                           (staging.path / "figures" / (stem + ".png")).string());
    }
    const fs::path script_path = staging.path / "figures.gp";
    const fs::path log_path = staging.path / "gnuplot.log";
    write_file(script_path, script);
    const std::string command = shell_quote(options.gnuplot) + " " +
                                shell_quote(script_path.string()) + " > " +
                                shell_quote(log_path.string()) + " 2>&1";
    const int status = std::system(command.c_str());
    bool all = status == 0;
    for (const auto& name : figure_files) all = all && fs::exists(staging.path / name, ec);
    if (!all) {
      const std::string log = slurp(log_path);
      if (status != 0 && (WEXITSTATUS(status) == 127)) {
        written.notes.push_back("static figures (SVG, PNG) skipped: gnuplot was not found (" +
                                options.gnuplot + "); install gnuplot-nox (scripts/setup.sh)");
        figure_files.clear();
      } else {
        throw std::runtime_error("gnuplot failed drawing the figures: " + log.substr(0, 600));
      }
    }
  }
  // Into place: figures and tables first, the two documents last.
  fs::create_directories(root / "figures", ec);
  std::vector<std::string> order = figure_files;
  for (const auto& [name, text] : texts) {
    if (name != "report.html" && name != "report.json") order.push_back(name);
  }
  order.push_back("report.html");
  if (texts.count("report.json") != 0) order.push_back("report.json");
  for (const auto& name : order) {
    fs::rename(staging.path / name, root / name);
    written.files.push_back(name);
  }
  return written;
}

WrittenReport write_report(const nlohmann::json& doc, const std::string& dir,
                           const WriteOptions& options) {
  // Everything to write, by path relative to DIR.
  std::map<std::string, std::string> texts;
  texts["report.json"] = doc.dump(1) + "\n";
  texts["report.md"] = render_markdown(doc);
  for (auto& [name, text] : render_csv_tables(doc)) texts[name] = std::move(text);
  if (doc["kalibr"]["written"].get<bool>()) texts["imu.yaml"] = doc["kalibr"]["text"];
  return write_report_files(
      std::move(texts), [&doc](const std::string& plotly) { return render_html(doc, plotly); },
      doc["figures"], dir, options);
}

}  // namespace imunoise::study
