// Command-line arguments as UTF-8 and user messages for a GUI exe: std handles, parent console, message box.
#pragma once

#include <string>
#include <vector>

namespace sr::win32 {

// The process's arguments after the program name, converted from UTF-16 to UTF-8.
std::vector<std::string> commandLineArguments();

// Writes text to the process's stdout / stderr: the inherited handle when there is one (pipe,
// file or console), else the console of the parent process (AttachConsole). Returns false when
// there is nowhere to write (started from Explorer).
bool writeStdout(const std::string& utf8);
bool writeStderr(const std::string& utf8);

// UTF-8 -> UTF-16 for the W functions (invalid sequences become U+FFFD).
std::wstring widen(const std::string& utf8);

// Shows a modal message box owned by no window (an error icon when isError).
void showMessageBox(const std::string& utf8, bool isError);

} // namespace sr::win32
