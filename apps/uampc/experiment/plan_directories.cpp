#include "experiment/plan_directories.hpp"

#include <algorithm>
#include <filesystem>
#include <system_error>
#include <utility>

namespace fs = std::filesystem;

namespace uampc::app {

namespace {

constexpr char kRunsDirectory[] = "runs";

// Absolute and lexically normal, without a trailing separator ("out/" is "out").
fs::path normalPath(const fs::path& path) {
  fs::path normal = fs::absolute(path).lexically_normal();
  if (!normal.has_filename() && normal != normal.root_path()) normal = normal.parent_path();
  return normal;
}

// Whether `path` lies inside `base`, not at it (both normal).
bool strictlyInside(const fs::path& path, const fs::path& base) {
  const fs::path relative = path.lexically_relative(base);
  return !relative.empty() && relative != "." && *relative.begin() != "..";
}

std::string entry(std::size_t index, const std::string& relative) {
  return "plan entry " + std::to_string(index) + " (" + relative + ")";
}

}  // namespace

std::string runDirectoryProblem(const std::string& output_directory, std::size_t index, const std::string& relative) {
  if (relative.empty()) return entry(index, relative) + ": no directory";
  if (fs::path(relative).is_absolute()) {
    return entry(index, relative) + ": an absolute path; a run's directory is relative to " + output_directory;
  }
  const fs::path out = normalPath(output_directory);
  const fs::path lexical = normalPath(out / relative);
  if (!strictlyInside(lexical, out / kRunsDirectory)) {
    return entry(index, relative) + ": " + lexical.string() + " is not inside " + (out / kRunsDirectory).string();
  }
  std::error_code error;
  const fs::path resolved_out = fs::weakly_canonical(out, error);
  const fs::path resolved = error ? fs::path() : fs::weakly_canonical(lexical, error);
  if (error) return entry(index, relative) + ": cannot resolve " + lexical.string() + ": " + error.message();
  if (!strictlyInside(normalPath(resolved), normalPath(resolved_out / kRunsDirectory))) {
    return entry(index, relative) + ": " + lexical.string() + " leads to " + resolved.string() +
           " (through a symbolic link), which is not inside " + (resolved_out / kRunsDirectory).string();
  }
  return "";
}

std::string planDirectoriesProblem(const std::string& output_directory, const std::vector<PlannedRun>& plan) {
  std::vector<std::pair<fs::path, std::size_t>> directories;
  for (std::size_t i = 0; i < plan.size(); ++i) {
    if (std::string problem = runDirectoryProblem(output_directory, i, plan[i].directory); !problem.empty()) {
      return problem;
    }
    directories.emplace_back(normalPath(fs::path(output_directory) / plan[i].directory), i);
  }
  // Sorted element by element, a directory's subdirectories follow it at once.
  std::sort(directories.begin(), directories.end());
  for (std::size_t k = 1; k < directories.size(); ++k) {
    const auto& [first, i] = directories[k - 1];
    const auto& [second, j] = directories[k];
    if (first == second || strictlyInside(second, first)) {
      return entry(i, plan[i].directory) + " and " + entry(j, plan[j].directory) +
             ": one run's directory would hold the other's";
    }
  }
  return "";
}

}  // namespace uampc::app
