#pragma once
// Starting the player for one stimulus. The study never plays media itself:
// it runs `hapcine play VIDEO --track TRACK --device DEVICE` as a child
// process (the same binary, found through /proc/self/exe) and waits for it,
// so a player crash cannot take the session — and its journal — down.
//
// The command is a template split on whitespace (single and double quotes
// group words; no shell is involved) in which {exe}, {video}, {track},
// {device}, {clip} and {condition} are replaced in every word.

#include <map>
#include <string>
#include <vector>

namespace hapcine::study {

constexpr const char* kDefaultPlayerTemplate =
    "{exe} play {video} --track {track} --device {device}";

// Splits a command template into words. Throws UsageError on an unclosed quote.
std::vector<std::string> SplitCommand(const std::string& command);
// Replaces every {key} of `vars` in every word.
std::vector<std::string> SubstituteCommand(const std::vector<std::string>& words,
                                           const std::map<std::string, std::string>& vars);
// The running executable (readlink /proc/self/exe); "hapcine" if unknown.
std::string SelfExecutable();
// Runs argv (argv[0] looked up on PATH if it has no slash) with the parent's
// stdin/stdout/stderr and waits. Returns the exit status, or 128 + signal if
// it was killed. Throws Error if it cannot be started.
int RunChild(const std::vector<std::string>& argv);

}  // namespace hapcine::study
