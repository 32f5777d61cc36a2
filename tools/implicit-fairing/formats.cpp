// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
#include "formats.h"

#include "common.h"

#include <algorithm>
#include <cctype>

namespace implicit_fairing {
namespace {

std::string lowerExtension(const std::string& path)
{
    const auto slash = path.find_last_of('/');
    const auto dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string ext = path.substr(dot + 1);
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

}  // namespace

Format formatOf(const std::string& path)
{
    const std::string ext = lowerExtension(path);
    if (ext == "ply") return Format::PLY;
    if (ext == "obj") return Format::OBJ;
    if (ext == "off") return Format::OFF;
    if (ext == "stl") return Format::STL;
    return Format::Unknown;
}

Format requireFormat(const std::string& path, const char* role)
{
    const Format f = formatOf(path);
    if (f == Format::Unknown) {
        const std::string ext = lowerExtension(path);
        throw Failure{std::string(role) + " " + path + ": " +
                      (ext.empty() ? std::string("no file extension")
                                   : "unsupported file extension '." + ext + "'") +
                      "; supported: .ply .obj .off .stl"};
    }
    return f;
}

const char* formatName(Format f)
{
    switch (f) {
    case Format::PLY: return "PLY";
    case Format::OBJ: return "OBJ";
    case Format::OFF: return "OFF";
    case Format::STL: return "STL";
    default: return "?";
    }
}

}  // namespace implicit_fairing
