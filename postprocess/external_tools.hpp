// The helper programs the postprocessor runs: its Python scripts (shipped next to the
// executable at build time), /usr/bin/python3 for matplotlib and ParaView's pvbatch under
// xvfb-run for figures. A missing tool is an ExternalToolError with the package to install.
#pragma once
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace mppm::post {

class ExternalToolError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Directory of the running executable (/proc/self/exe).
std::string executable_directory();

// `directory`/`name` if it exists (directory empty: next to the executable); otherwise throws
// ExternalToolError saying the installation is incomplete.
std::string companion_script(const std::string& name, const std::string& directory = {});

// A temporary name next to `path` for a tool's output: hidden, with the process id, and with
// the extension kept (matplotlib, ParaView and PIL choose the format by it).
std::string temporary_with_extension(const std::string& path);

// Full path of `program` found on PATH, if any.
std::optional<std::string> find_program(const std::string& program);

// Runs argv[0] with the arguments, waits, returns the exit status (128 + signal if killed).
// With `quiet`, the child's stdout goes to /dev/null; stderr is always passed through.
// `environment` entries ("NAME=value") are added to (or replace in) the child's environment.
int run_program(const std::vector<std::string>& argv, bool quiet, const std::vector<std::string>& environment = {});

// Where pvbatch finds ParaView's Python modules. Debian 12's python3-paraview conflicts with
// python3-vtk9 (which libvtk9-dev needs), so the build machine keeps it unpacked aside:
//   apt-get download python3-paraview && dpkg -x python3-paraview_*.deb /opt/paraview-python
// Returns the environment entries for pvbatch ({} when python3-paraview is installed), or
// throws ExternalToolError explaining the above. $MPPM_PARAVIEW_PYTHONPATH overrides the search.
std::vector<std::string> paraview_python_environment();

}  // namespace mppm::post
