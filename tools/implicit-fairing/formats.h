// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Mesh file formats, chosen by file extension (any case).
#pragma once

#include <string>

namespace implicit_fairing {

enum class Format { Unknown, PLY, OBJ, OFF, STL };

Format formatOf(const std::string& path);
// formatOf(path), or throws Failure naming the role ("input", "output") and the extensions.
Format requireFormat(const std::string& path, const char* role);
const char* formatName(Format f);

}  // namespace implicit_fairing
