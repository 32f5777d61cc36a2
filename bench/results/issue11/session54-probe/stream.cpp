// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// auto-gap.md section 54: what one thread streams on this host (a dot product reads two arrays of
// 2^25 doubles; a triad reads two and writes one), five rounds.
// g++ -O3 -o /tmp/stream stream.cpp && /tmp/stream > stream.txt
#include <vector>
#include <chrono>
#include <cstdio>
int main(){ const size_t n=1<<25; std::vector<double> a(n,1.0),b(n,2.0),c(n,0.0);
 for(int r=0;r<5;r++){ auto t=std::chrono::steady_clock::now();
  double s=0; for(size_t i=0;i<n;i++) s+=a[i]*b[i];
  double dt=std::chrono::duration<double>(std::chrono::steady_clock::now()-t).count();
  auto t2=std::chrono::steady_clock::now();
  for(size_t i=0;i<n;i++) c[i]=a[i]+0.5*b[i];
  double dt2=std::chrono::duration<double>(std::chrono::steady_clock::now()-t2).count();
  std::printf("dot read %.1f GB/s  triad %.1f GB/s (%g)\n", 2*n*8/dt/1e9, 3*n*8/dt2/1e9, s+c[5]);}
}
