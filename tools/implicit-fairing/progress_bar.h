// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// A one-line progress bar on stderr: "implicit-fairing [#####     ]  50%", redrawn only when the
// percentage changes, erased by clear() (or the destructor). Disabled, it prints nothing; the
// tool enables it only when stderr is a terminal. (Debian 12 packages no C++ progress-bar
// library; this is the whole of ours, tested by tests/cli's "progress" case under a terminal.)
#pragma once

namespace implicit_fairing {

class ProgressBar {
public:
    explicit ProgressBar(bool enabled) : enabled_(enabled) {}
    ~ProgressBar() { clear(); }
    ProgressBar(const ProgressBar&) = delete;
    ProgressBar& operator=(const ProgressBar&) = delete;

    void update(double fraction);  // fraction of the work done, clamped to [0, 1]
    void clear();

private:
    bool enabled_;
    bool drawn_ = false;
    int percent_ = -1;
};

}  // namespace implicit_fairing
