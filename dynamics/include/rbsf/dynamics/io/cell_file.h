#pragma once
/// \file
/// \brief Cell files: a Cell (cell.h) read from YAML, checked by Cell::validate().

#include <string>

#include "rbsf/dynamics/core/cell.h"

namespace rbsf {

/// \brief Read a cell from a YAML file (format in docs/model.md "Files", with the optional
///        sections `sensing` and `uncertainty` of sensing.h).
/// \throws InputError for a missing file, malformed YAML, a missing or non-numeric key,
///         or an invalid value; the message names the key (e.g. "fingers[1].mass").
Cell loadCell(const std::string& path);

/// \brief Read a cell from YAML text; `label` names the source in messages.
Cell parseCell(const std::string& yaml_text, const std::string& label = "<cell>");

}  // namespace rbsf
