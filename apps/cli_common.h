#pragma once
// What the tetrender subcommands share: progress on a terminal, the exit codes, and printing
// what the library returns (errors, notes, stats). Loading and rendering are the library's
// (pipeline/).

#include <core/progress.h>
#include <core/result.h>
#include <pipeline/loaded_mesh.h>
#include <pipeline/render_stats.h>

#include <string>
#include <vector>

namespace tr::apps {

// Exit codes of every subcommand (README documents them).
inline constexpr int kExitOk = 0;
inline constexpr int kExitError = 1;  // bad input or a failure: one line on stderr says why
inline constexpr int kExitUsage = 2;  // bad command line

// A progress callback that draws "stage NN%" on stderr when stderr is a terminal (nothing
// otherwise, so logs and pipes stay clean).
ProgressFn terminal_progress();

// Whether `path` names a scene file (.json) rather than a mesh: how render and the viewer tell
// a scene from a quick look.
bool is_scene_file(const std::string& path);

// Parses "WxH" with both sides in [1, kMaxImageSide] (pipeline/scene.h).
bool parse_image_size(const std::string& text, int& width, int& height);

// Checks, before any work, that `path` can be written: its extension is one of `extensions`
// (".png", ...; case-sensitive), its folder exists and a file can be made in it (a probe file,
// removed at once). Error kInvalidArgument saying which.
Status check_output_path(const std::string& path, const std::vector<std::string>& extensions);

// The name the messages below start with: "tetrender" (default) or "tetrender-view".
void set_program_name(const char* name);

// Prints "<program>: <error>" on stderr, returns kExitError.
int report_error(const Error& error);

// Prints "<program>: <error>" on stderr, returns kExitUsage: a bad command-line value.
int report_usage(const Error& error);

// Prints each note as "<program>: note: ..." on stderr.
void print_notes(const std::vector<std::string>& notes);

// Prints the stats as one JSON object on stdout.
void print_stats(const NamedStats& stats);

}  // namespace tr::apps
