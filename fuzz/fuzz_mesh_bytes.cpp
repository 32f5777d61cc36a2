// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// libFuzzer target (issue 6): mesh bytes -> vcg mesh (as MeshLab holds it: float coordinates,
// deleted/selected flags, per-vertex quality) -> vcg_adapters -> fairing::fair (a short run)
// -> writePositions. It must never crash, hang, or write a non-finite coordinate; a
// fairing::Error is a fine outcome, but then the vcg mesh must be bit-identical.
//
// Byte format (read front to back; missing bytes read as 0, counts shrink to the bytes there):
//   b0  op = b0 % 3, order = 1 + bit2 (+ 2 with b2's bit7), explicit = bit3 & bit4,
//       normalized = explicit & bit5, preserve_volume = !bit6, accept_unconverged = bit7
//   b1  boundary = b1 % 3, open invariant area = bit2, freeze = bit3, only selected = bit4,
//       quality weights = bit5, invert quality = bit6, raw float coordinates = bit7
//   b2  time step = kTimeSteps[b2 & 7], steps = 1 + bit3, tolerance = kTolerances[(b2>>4)&3],
//       L-infinity norm = bit6, order + 2 (L^3, L^4) = bit7
//   b3  max_iterations = 1 + b3 % 64
//   u16 vertex count (<= 2000), u16 face count (<= 4000), little endian
//   per vertex: 3 int8 / 8 (lattice) or 3 raw float32 bits (NaN, Inf, huge, denormal), then a
//       flag byte: 0xFF deleted, 0xFE quality NaN, else bit0 selected, quality = (b>>1)/32 - 0.5
//   per face: 3 u16 vertex indices (mod vertex count), a flag byte: 0xFF deleted, bit0 selected
#include <fairing/fairing.h>
#include <vcg_adapters/vcg_adapters.h>

#include <vcg/complex/complex.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <vector>

namespace {

class FVertex;
class FFace;
struct FUsedTypes : public vcg::UsedTypes<vcg::Use<FVertex>::AsVertexType,
                                          vcg::Use<FFace>::AsFaceType> {};
class FVertex : public vcg::Vertex<FUsedTypes, vcg::vertex::Coord3f, vcg::vertex::Normal3f,
                                   vcg::vertex::Qualityf, vcg::vertex::BitFlags> {};
class FFace : public vcg::Face<FUsedTypes, vcg::face::VertexRef, vcg::face::Normal3f,
                               vcg::face::BitFlags> {};
class FMesh : public vcg::tri::TriMesh<std::vector<FVertex>, std::vector<FFace>> {};

constexpr int kMaxVertices = 2000;
constexpr int kMaxFaces = 4000;
const double kTimeSteps[8] = {0.0, 1e-3, 0.5, 1.0, 10.0, 22.5, 1e6, 1e12};
const double kTolerances[4] = {1e-8, 1e-4, 1e-12, 0.0};

struct Reader {
    const std::uint8_t* p;
    std::size_t n;
    std::size_t left() const { return n; }
    std::uint8_t u8() {
        if (n == 0) return 0;
        --n;
        return *p++;
    }
    std::uint16_t u16() { return static_cast<std::uint16_t>(u8() | (u8() << 8)); }
    float f32() {
        std::uint32_t bits = 0;
        for (int k = 0; k < 4; ++k) bits |= static_cast<std::uint32_t>(u8()) << (8 * k);
        float f;
        std::memcpy(&f, &bits, sizeof f);
        return f;
    }
};

[[noreturn]] void die(const char* what) {
    std::fprintf(stderr, "fuzz_mesh_bytes: %s\n", what);
    std::abort();
}

std::vector<std::uint32_t> coordinate_bits(const FMesh& m) {
    std::vector<std::uint32_t> bits;
    for (const FVertex& v : m.vert)
        for (int k = 0; k < 3; ++k) {
            std::uint32_t b;
            const float x = v.cP()[k];
            std::memcpy(&b, &x, sizeof b);
            bits.push_back(b);
        }
    return bits;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    Reader in{data, size};
    const std::uint8_t b0 = in.u8(), b1 = in.u8(), b2 = in.u8(), b3 = in.u8();
    fairing::Options o;
    o.op = static_cast<fairing::Operator>(b0 % 3);
    o.order = 1 + ((b0 >> 2) & 1) + 2 * ((b2 >> 7) & 1);
    const bool explicit_steps = ((b0 >> 3) & 1) && ((b0 >> 4) & 1);
    o.integration = explicit_steps ? fairing::Integration::Explicit : fairing::Integration::Implicit;
    o.normalized = explicit_steps && ((b0 >> 5) & 1);
    o.preserve_volume = !((b0 >> 6) & 1);
    o.accept_unconverged = (b0 >> 7) & 1;
    o.boundary = static_cast<fairing::BoundaryMode>(b1 % 3);
    o.open_invariant = ((b1 >> 2) & 1) ? fairing::OpenInvariant::Area : fairing::OpenInvariant::None;
    o.freeze_operator = (b1 >> 3) & 1;
    vcg_adapters::ConstraintSettings cs;
    cs.onlySelected = (b1 >> 4) & 1;
    cs.qualityWeights = (b1 >> 5) & 1;
    cs.invertQuality = (b1 >> 6) & 1;
    const bool raw = (b1 >> 7) & 1;
    o.time_step = kTimeSteps[b2 & 7];
    o.steps = 1 + ((b2 >> 3) & 1);
    o.tolerance = kTolerances[(b2 >> 4) & 3];
    o.norm = ((b2 >> 6) & 1) ? fairing::ResidualNorm::LInfinity : fairing::ResidualNorm::L2;
    o.max_iterations = 1 + b3 % 64;

    const std::size_t vertex_bytes = raw ? 13 : 4;
    int nv = in.u16() % (kMaxVertices + 1);
    int nf = in.u16() % (kMaxFaces + 1);
    nv = static_cast<int>(std::min<std::size_t>(nv, in.left() / vertex_bytes));

    FMesh m;
    std::vector<char> deleted(nv, 0);
    vcg::tri::Allocator<FMesh>::AddVertices(m, nv);
    for (int i = 0; i < nv; ++i) {
        FVertex& v = m.vert[i];
        for (int k = 0; k < 3; ++k)
            v.P()[k] = raw ? in.f32() : static_cast<float>(static_cast<std::int8_t>(in.u8())) / 8.0f;
        const std::uint8_t f = in.u8();
        v.Q() = f == 0xFE ? std::numeric_limits<float>::quiet_NaN()
                          : static_cast<float>(f >> 1) / 32.0f - 0.5f;
        if (f == 0xFF) deleted[i] = 1;
        else if (f & 1) v.SetS();
    }
    nf = nv == 0 ? 0 : static_cast<int>(std::min<std::size_t>(nf, in.left() / 7));
    if (nf > 0) vcg::tri::Allocator<FMesh>::AddFaces(m, nf);
    for (int i = 0; i < nf; ++i) {
        FFace& f = m.face[i];
        for (int k = 0; k < 3; ++k) f.V(k) = &m.vert[in.u16() % nv];
        const std::uint8_t flags = in.u8();
        if (flags == 0xFF) vcg::tri::Allocator<FMesh>::DeleteFace(m, f);
        else if (flags & 1) f.SetS();
    }
    // deleted vertices last, so that faces may refer to them (the adapter must refuse)
    for (int i = 0; i < nv; ++i)
        if (deleted[i]) vcg::tri::Allocator<FMesh>::DeleteVertex(m, m.vert[i]);

    const std::vector<std::uint32_t> before = coordinate_bits(m);
    try {
        vcg_adapters::IndexMap map;
        const fairing::TriangleMesh tm = vcg_adapters::toTriangleMesh(m, map);
        const fairing::Constraints c = vcg_adapters::makeConstraints(m, map, cs);
        const fairing::Result r = fairing::fair(tm, c, o);
        if (r.positions.rows() != tm.positions.rows()) die("wrong number of positions");
        if (!r.positions.allFinite()) die("a successful result has a non-finite position");
        vcg_adapters::writePositions(m, map, r.positions);
        for (const FVertex& v : m.vert)
            if (!v.IsD() && !(std::isfinite(v.cP()[0]) && std::isfinite(v.cP()[1]) &&
                              std::isfinite(v.cP()[2])))
                die("a non-finite coordinate was written");
    } catch (const fairing::Error&) {
        if (coordinate_bits(m) != before) die("a refusal changed the mesh");
    }
    return 0;
}
