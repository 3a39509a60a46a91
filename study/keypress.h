#pragma once
// One key press from a terminal, without Enter (the paper's participants
// "select the favorite sequence by pressing a button").

#include <optional>

namespace hapcine::study {

// True if fd is a terminal (then ReadKeyPress can be used on it).
bool IsTerminal(int fd);

// Discards whatever was typed before (keys pressed while a stimulus played
// must not answer the question), then waits for one key on terminal fd with
// echo and line buffering off, and restores the terminal settings before
// returning. Ctrl-C and Ctrl-D are returned as bytes (3, 4) rather than
// raising a signal, so the caller can stop cleanly with the terminal intact.
// nullopt on end of file or a read error.
std::optional<char> ReadKeyPress(int fd);

}  // namespace hapcine::study
