// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// The temporary output: a private folder created next to OUT before the work starts (so an
// unwritable folder fails early), holding a file with OUT's own name (the OBJ exporter writes
// the name into the file). commit() renames the file over OUT; otherwise the destructor, or
// SIGINT, SIGTERM or SIGHUP, removes the file and the folder. One TempFile at a time.
#pragma once

#include <string>

namespace implicit_fairing {

class TempFile {
public:
    explicit TempFile(const std::string& out);  // throws Failure
    ~TempFile();
    TempFile(const TempFile&) = delete;
    TempFile& operator=(const TempFile&) = delete;

    const std::string& path() const { return path_; }
    void commit();  // throws Failure

private:
    std::string out_, dir_, path_;
};

}  // namespace implicit_fairing
