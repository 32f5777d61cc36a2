// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// fairing::Error in the words of the host that shows it: when the engine refuses input that a
// cleaning filter repairs (fairing::Repair), the message names that filter as the user calls it
// there. MeshLab 2020.09 and 2025.07 name some filters differently in their menus, and
// pymeshlab calls them by python name. Every name below was checked in that version's sources
// (meshlabplugins/filter_clean/cleanfilter.cpp, filter_select/meshselect.cpp,
// filter_func/filter_func.cpp: filterName() and pythonFilterName()).
#pragma once

#include <fairing/types.h>

#include <string>
#include <vector>

namespace filter_parameters {

enum class Host {
    MeshLab2020,  // Debian 12's MeshLab 2020.09: GUI and meshlabserver, menu text
    MeshLab2025,  // the MeshLab 2025.07 GUI, menu text
    Pymeshlab,    // pymeshlab 2025.7: python names, as methods of the MeshSet `ms`
    CommandLine,  // implicit-fairing: MeshLab 2025.07's menu text and the pymeshlab name
};

// One filter of a repair: its menu entry in each MeshLab and its pymeshlab call.
struct RepairStep {
    const char* menu2020;
    const char* menu2025;
    const char* menuPath;  // where both menus put it
    const char* python;    // with its arguments
    const char* settings;  // what to set in the dialog, or ""
};

inline std::vector<RepairStep> repairSteps(fairing::Repair r)
{
    // MeshLab's muparser condition that selects NaN (x != x) and infinite coordinates
#define FAIRING_NON_FINITE "x != x || y != y || z != z || abs(x) + abs(y) + abs(z) > 1e38"
    switch (r) {
    case fairing::Repair::NonManifoldEdges:
        return {{"Repair non Manifold Edges by removing faces", "Repair non Manifold Edges",
                 "Filters > Cleaning and Repairing", "meshing_repair_non_manifold_edges()", ""}};
    case fairing::Repair::NonManifoldVertices:
        return {{"Repair non Manifold Vertices by splitting",
                 "Repair non Manifold Vertices by splitting", "Filters > Cleaning and Repairing",
                 "meshing_repair_non_manifold_vertices()", ""}};
    case fairing::Repair::DuplicateFaces:
        return {{"Remove Duplicate Faces", "Remove Duplicate Faces",
                 "Filters > Cleaning and Repairing", "meshing_remove_duplicate_faces()", ""}};
    case fairing::Repair::NonFiniteVertices:
        return {{"Conditional Vertex Selection", "Conditional Vertex Selection",
                 "Filters > Selection",
                 "compute_selection_by_condition_per_vertex(condselect='" FAIRING_NON_FINITE "')",
                 " with " FAIRING_NON_FINITE},
                {"Delete Selected Vertices", "Delete Selected Vertices", "Filters > Selection",
                 "meshing_remove_selected_vertices()", ""}};
    case fairing::Repair::None: break;
    }
#undef FAIRING_NON_FINITE
    return {};
}

// "MeshLab's 'Repair non Manifold Edges' filter (Filters > Cleaning and Repairing)" or
// "ms.meshing_repair_non_manifold_edges()".
inline std::string describe(const RepairStep& s, Host host)
{
    const std::string menu = host == Host::MeshLab2020 ? s.menu2020 : s.menu2025;
    const std::string gui = "MeshLab's '" + menu + "' filter (" + s.menuPath + ")" + s.settings;
    switch (host) {
    case Host::Pymeshlab: return std::string("ms.") + s.python;
    case Host::CommandLine: return gui + " or pymeshlab's ms." + s.python;
    default: return gui;
    }
}

// e.what(), with the repair named for host: "<problem>; run <filter>[, then <filter>] first".
inline std::string render(const fairing::Error& e, Host host)
{
    const std::vector<RepairStep> steps = repairSteps(e.repair());
    if (steps.empty()) return e.what();
    std::string out = e.problem() + "; run ";
    for (std::size_t i = 0; i < steps.size(); ++i)
        out += (i ? ", then " : "") + describe(steps[i], host);
    out += " first";
    if (!e.alternative().empty()) out += ", or " + e.alternative();
    return out;
}

}  // namespace filter_parameters
