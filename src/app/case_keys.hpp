// The reference of every case key (`cgdem keys`, committed as docs/case_keys.md): name,
// type, unit, default, allowed values and meaning, generated from the readers themselves.
//
// The readers of a case (read_dem_case, read_air_case, read_diagnostics; read_flow_case)
// run on a few built-in cases that together take every path through them, with the
// Config's KeyLog noting each key as its accessor is called: type, default and range are
// the ones that accessor validates. Units and meanings come from a table beside the
// readers (case_key_docs.cpp), checked against the keys read: a key read without an entry,
// or an entry that no reader asks for, stops the generation with its name. The test
// `docs.case_keys_up_to_date` compares the output with the committed file.
#pragma once
#include <string>
#include <vector>

#include "core/config.hpp"

namespace cgdem::app {

// The unit and meaning of one key (path as KeyUse::path).
struct KeyDoc {
  const char* path;
  const char* unit;     // SI, "1" for a count or a ratio, "" for none (strings, booleans)
  const char* meaning;
  const char* default_note = nullptr;  // replaces the default when it depends on other keys
};
// The table of every key's unit and meaning (case_key_docs.cpp).
const std::vector<KeyDoc>& case_key_docs();

// Runs the readers of a case: a flow case ([flow]) or a case with parcels, with or without
// air and die-filling diagnostics. Throws ConfigError as they do.
void read_case(Config& cfg);

// The keys the readers ask of a case file: of a case with parcels (with or without air) or
// of a flow case ([flow]), in the order asked. Throws ConfigError as the readers do.
std::vector<KeyUse> keys_read(Config& cfg);

// docs/case_keys.md (Markdown). Throws cgdem::Error naming any key without an entry in
// case_key_docs() and any entry no reader asks for.
std::string case_key_reference();

// The keys that reading `case_file` asks for and the reference lacks (empty: none).
std::vector<std::string> undocumented_keys(const std::string& case_file);

// `cgdem keys [--output FILE] [--check CASE ...]`: prints the reference (or writes it to
// FILE); with --check, lists the keys of the cases that the reference lacks instead, and
// returns 1 when there are any.
int keys_command(const std::string& output, const std::vector<std::string>& check);

}  // namespace cgdem::app
