// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
#include "temp_file.h"

#include "common.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <vector>

namespace implicit_fairing {
namespace {

// The signal handler may only touch plain buffers, not std::string.
char g_tempFile[PATH_MAX + 64] = {0};
char g_tempDir[PATH_MAX + 64] = {0};

extern "C" void removeTempAndReraise(int sig)
{
    if (g_tempFile[0]) unlink(g_tempFile);
    if (g_tempDir[0]) rmdir(g_tempDir);
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}

}  // namespace

TempFile::TempFile(const std::string& out) : out_(out)
{
    const auto slash = out.find_last_of('/');
    const std::string dir = slash == std::string::npos ? "" : out.substr(0, slash + 1);
    const std::string base = slash == std::string::npos ? out : out.substr(slash + 1);
    if (base.empty()) throw Failure{"output " + out + ": no file name"};
    const std::string templ = dir + "." + base + ".tmp-XXXXXX";
    if (templ.size() + base.size() + 2 >= sizeof(g_tempFile))
        throw Failure{"output path too long: " + out};
    std::vector<char> buf(templ.begin(), templ.end());
    buf.push_back('\0');
    if (!mkdtemp(buf.data()))
        throw Failure{"cannot create a file in " + (dir.empty() ? std::string(".") : dir) +
                      " (for " + out + "): " + std::strerror(errno)};
    dir_ = buf.data();
    path_ = dir_ + "/" + base;
    std::memcpy(g_tempDir, dir_.c_str(), dir_.size() + 1);
    std::memcpy(g_tempFile, path_.c_str(), path_.size() + 1);
    std::signal(SIGINT, removeTempAndReraise);
    std::signal(SIGTERM, removeTempAndReraise);
    std::signal(SIGHUP, removeTempAndReraise);
}

TempFile::~TempFile()
{
    if (!path_.empty()) unlink(path_.c_str());
    if (!dir_.empty()) rmdir(dir_.c_str());
    g_tempFile[0] = g_tempDir[0] = '\0';
}

void TempFile::commit()
{
    struct stat st;
    if (stat(out_.c_str(), &st) == 0) chmod(path_.c_str(), st.st_mode & 07777);
    if (std::rename(path_.c_str(), out_.c_str()) != 0)
        throw Failure{"cannot rename " + path_ + " to " + out_ + ": " + std::strerror(errno)};
    path_.clear();
    g_tempFile[0] = '\0';
}

}  // namespace implicit_fairing
