#pragma once
/// \file
/// \brief What every rbsf command-line tool shares: option parsing with the project's
///        conventions, one error message and a documented exit status.
///
/// Exit status of every tool: 0 success; 2 bad input (an option, a value, a file, a
/// state the model refuses), with one message "<tool>: error: ..." on stderr; 1 an
/// internal error. Tools add their own codes above 2 (documented in their --help).

#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

namespace rbsf::tools {

/// \brief Exit status for bad input.
inline constexpr int kExitBadInput = 2;
/// \brief Exit status for an internal error.
inline constexpr int kExitInternal = 1;

/// \brief The exit-status paragraph of every tool's --help.
inline constexpr const char* kExitStatusHelp =
    "Exit status: 0 success; 2 bad input (option, value, file or state), with one message "
    "on stderr; 1 internal error.";

/// \brief Thrown by parseCommandLine() when --help was printed.
struct HelpPrinted {};

/// \brief Parse argv with CLI11; option values may start with a minus sign and options
///        take both "--name value" and "--name=value". A CLI11 parse error becomes an
///        InputError naming the option; --help prints the help and throws HelpPrinted.
void parseCommandLine(CLI::App& app, int argc, char** argv);

/// \brief Run `body`, mapping InputError (and CLI errors) to exit status 2 and any other
///        exception to 1, each with one line "<name>: error: <message>" on stderr.
int toolMain(const char* name, int argc, char** argv, const std::function<int(int, char**)>& body);

/// \brief A JSON array of an Eigen vector's entries.
nlohmann::json vectorJson(const Eigen::Ref<const Eigen::VectorXd>& v);

/// \brief True when every number in `j` is finite.
bool allFinite(const nlohmann::json& j);

/// \brief Throw std::runtime_error naming `what` if `j` holds a NaN or an infinity
///        anywhere (outputs never carry NaN).
void requireFinite(const nlohmann::json& j, const std::string& what);

}  // namespace rbsf::tools
