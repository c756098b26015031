// fork/exec rather than std::system: no shell, so paths with spaces or quotes are safe.
#include "postprocess/external_tools.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>

namespace mppm::post {
namespace fs = std::filesystem;

std::string executable_directory() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return fs::current_path().string();
  return self.parent_path().string();
}

std::string companion_script(const std::string& name, const std::string& directory) {
  const fs::path path = fs::path(directory.empty() ? executable_directory() : directory) / name;
  if (!fs::exists(path))
    throw ExternalToolError("the helper script " + path.string() +
                            " is missing: the build copies it next to mppm-postprocess "
                            "(rebuild, or keep it next to the executable when copying it)");
  return path.string();
}

std::string temporary_with_extension(const std::string& path) {
  const fs::path file(path);
  // Built by appending: GCC 12 warns falsely (-Wrestrict, PR105329) on "." + std::string.
  std::string name(1, '.');
  name += file.stem().string();
  name += ".tmp-";
  name += std::to_string(::getpid());
  name += file.extension().string();
  return (file.parent_path() / name).string();
}

std::optional<std::string> find_program(const std::string& program) {
  if (program.find('/') != std::string::npos)
    return ::access(program.c_str(), X_OK) == 0 ? std::optional<std::string>(program) : std::nullopt;
  const char* path = std::getenv("PATH");
  std::istringstream directories(path ? path : "/usr/local/bin:/usr/bin:/bin");
  std::string directory;
  while (std::getline(directories, directory, ':')) {
    if (directory.empty()) continue;
    const std::string candidate = directory + "/" + program;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return std::nullopt;
}

std::vector<std::string> paraview_python_environment() {
  const auto has_paraview = [](const fs::path& directory) { return fs::exists(directory / "paraview" / "simple.py"); };
  std::vector<fs::path> candidates;
  if (const char* configured = std::getenv("MPPM_PARAVIEW_PYTHONPATH")) candidates.emplace_back(configured);
  candidates.emplace_back("/opt/paraview-python/usr/lib/python3/dist-packages");
  if (has_paraview("/usr/lib/python3/dist-packages")) return {};
  for (const auto& candidate : candidates)
    if (has_paraview(candidate)) {
      std::string path = "PYTHONPATH=" + candidate.string();
      if (const char* existing = std::getenv("PYTHONPATH"); existing && *existing) path += std::string(":") + existing;
      return {path};
    }
  throw ExternalToolError(
      "pvbatch cannot find ParaView's Python modules (package python3-paraview). Debian 12's "
      "python3-paraview conflicts with python3-vtk9, which libvtk9-dev needs, so unpack it aside: "
      "'apt-get download python3-paraview && dpkg -x python3-paraview_*.deb /opt/paraview-python' "
      "(or set MPPM_PARAVIEW_PYTHONPATH to a directory holding paraview/simple.py)");
}

int run_program(const std::vector<std::string>& argv, bool quiet, const std::vector<std::string>& environment) {
  if (argv.empty()) throw ExternalToolError("run_program: nothing to run");
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  // The child's environment, built before fork (nothing but exec after fork).
  std::vector<std::string> variables;
  for (char** e = environ; *e; ++e) {
    const std::string entry(*e);
    bool replaced = false;
    for (const auto& extra : environment)
      if (entry.substr(0, entry.find('=') + 1) == extra.substr(0, extra.find('=') + 1)) replaced = true;
    if (!replaced) variables.push_back(entry);
  }
  variables.insert(variables.end(), environment.begin(), environment.end());
  std::vector<char*> envp;
  for (auto& v : variables) envp.push_back(v.data());
  envp.push_back(nullptr);
  const pid_t child = ::fork();
  if (child < 0) throw ExternalToolError("cannot start " + argv[0] + ": " + std::strerror(errno));
  if (child == 0) {
    if (quiet) {
      const int null = ::open("/dev/null", O_WRONLY);
      if (null >= 0) ::dup2(null, STDOUT_FILENO);
    }
    ::execve(args[0], args.data(), envp.data());
    std::_Exit(127);
  }
  int status = 0;
  while (::waitpid(child, &status, 0) < 0)
    if (errno != EINTR) throw ExternalToolError("waiting for " + argv[0] + ": " + std::strerror(errno));
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 1;
}

}  // namespace mppm::post
