// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
#include "progress_bar.h"

#include "common.h"

#include <algorithm>
#include <cstdio>
#include <string>

namespace implicit_fairing {

void ProgressBar::update(double fraction)
{
    if (!enabled_) return;
    fraction = std::min(1.0, std::max(0.0, fraction));
    const int percent = static_cast<int>(fraction * 100 + 0.5);
    if (drawn_ && percent == percent_) return;
    percent_ = percent;
    const int width = 30, filled = static_cast<int>(fraction * width + 0.5);
    std::fprintf(stderr, "\r%s [%s%s] %3d%%", kTool, std::string(filled, '#').c_str(),
                 std::string(width - filled, ' ').c_str(), percent);
    std::fflush(stderr);
    drawn_ = true;
}

void ProgressBar::clear()
{
    if (enabled_ && drawn_) {
        std::fprintf(stderr, "\r\033[K");  // back to the line's start, erase to its end
        std::fflush(stderr);
    }
    drawn_ = false;
}

}  // namespace implicit_fairing
