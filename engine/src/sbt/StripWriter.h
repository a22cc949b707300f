#pragma once
// The strip writer (private to the sbt module): how a chunk's walk appends
// vertices to its generalized triangle strip, and how the chunks' strips are
// joined into the refinement's output.
//
//   Refiner::Chunk    one chunk's strip buffer and counts
//   appendToStrip     the strip append (the one copy of Lindstrom and
//                     Pascucci's tstrip-append rule), for every walk
//   growBuffer        how a chunk's buffer, or the output, grows
//   StripJoin         the chunks' strips, in chunk order, into one mesh
//   copyStrip         a strip's copy to the place StripJoin gave it
//
// The walks (Walker.h and the *Walk.h beside it) write through
// appendToStrip; Refiner.cpp runs the chunks and joins them.

#include <sierra/sbt/Refiner.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

namespace sierra::sbt {

struct Refiner::Chunk {
    std::vector<uint32_t> buffer;  // strip indices from `offset` on, capacity reused
    std::vector<uint32_t> starts;  // offset of every strip, from buffer.data() + offset
    size_t offset = 0;             // where the chunk's strips start in buffer
    // The buffer is the refinement's output (one thread): it grows by a
    // quarter, not twice its size (see refineSerially, Refiner.cpp).
    bool isOutput = false;
    int64_t used = 0;
    int64_t leaves = 0;
    int64_t culled = 0;  // subtrees culled in this chunk (view mode)
};

// The parity of a strip's last append, as Walker keeps it: its own int, -1
// when nothing was appended since the strip started. kOffset: what the
// stored value adds to the parity.
struct StripParity {
    static constexpr int kOffset = 0;
    int& parity;
    int stored() const { return parity; }
    void store(int value) const { parity = value; }
};

// The same parity as the keyed walk keeps it (KeyedWalk.h): plus one, in the
// low 2 bits of the state it hands back (0: nothing appended yet), the bits
// above counting its leaves.
struct PackedStripParity {
    static constexpr int kOffset = 1;
    int64_t& state;
    int stored() const { return int(state & 3); }
    void store(int value) const { state = (state & ~int64_t(3)) | value; }
};

// Appends vertex v, of level parity p (0 or 1), to the strip that ends at o
// (o[-1], o[-2]: its last two vertices; room for two more): nothing when v is
// one of the last two; when p equals the parity of the previous append the
// second-last vertex is re-sent first, so that the strip turns (Lindstrom and
// Pascucci's tstrip-append); o moves to the strip's new end. Inlined into
// every walk. o is the walk's own end pointer, written only when a vertex
// goes out, and the re-send is marked unlikely (out of line): so each walk
// compiles to the code of the rule written out in it (returning the new end,
// or with the re-send in line, the full-grid refinement ran 3% more
// instructions).
template <typename Parity>
[[gnu::always_inline]] inline void appendToStrip(uint32_t*& o, uint32_t v, int p, Parity last) {
    if (v == o[-1] || v == o[-2]) return;
    if (p + Parity::kOffset == last.stored()) [[unlikely]] {
        o[0] = o[-2];  // re-send: the strip turns
        ++o;
    } else {
        last.store(p + Parity::kOffset);
    }
    *o++ = v;
}

// Grows a buffer to at least `need` indices: by a quarter of its size, or
// within its capacity, for the refinement's output (isOutput), which would
// otherwise double its capacity when resized past it (56 MB more on a full
// 2049^2 grid, written once over and so faulted in); twice its size for a
// chunk's own buffer.
inline void growBuffer(std::vector<uint32_t>& buf, size_t need, bool isOutput) {
    if (!isOutput) {
        buf.resize(std::max(buf.size() * 2, need));
        return;
    }
    const size_t quarter = buf.size() + buf.size() / 4;
    if (need <= buf.capacity()) {
        buf.resize(std::min(buf.capacity(), std::max(need, quarter)));
        return;
    }
    buf.reserve(std::max(need, quarter));
    buf.resize(buf.capacity());
}

// The first non-degenerate triangle (s[k], s[k+1], s[k+2]) of the strip
// s[0..count): its offset k and its orientation in the (i, j) plane as written
// (> 0 counter-clockwise); 0 when the strip draws nothing.
inline int64_t firstTriangle(const uint32_t* s, int64_t count, uint32_t side, int64_t* offset) {
    for (int64_t k = 0; k + 2 < count; ++k) {
        uint32_t v0 = s[k], v1 = s[k + 1], v2 = s[k + 2];
        if (v0 == v1 || v1 == v2 || v0 == v2) continue;
        *offset = k;
        int64_t i0 = v0 % side, j0 = v0 / side, i1 = v1 % side, j1 = v1 / side, i2 = v2 % side,
                j2 = v2 / side;
        return (i1 - i0) * (j2 - j0) - (j1 - j0) * (i2 - i0);
    }
    return 0;
}

// Joins the chunks' strips, in chunk order, into one strip mesh. Every strip
// starts with its entry vertex twice (a, a); dropping one copy flips the GL
// parity of the whole strip, which is how each strip is made to decode
// clockwise in (i, j). A strip whose entry is the previous strip's last vertex
// and whose first triangle shares an edge with the previous one (consecutive
// subtrees on the curve, no culled gap between them) continues that strip
// through degenerate triangles instead of a restart. `place` decides where each
// strip of a chunk goes (it needs only the last three indices written, kept in
// `tail`) and hands that to `emit`, which copies it at once or later.
struct StripJoin {
    uint32_t side;
    int64_t pos = 0, stripStart = 0;
    uint32_t tail[3] = {kRestartIndex, kRestartIndex,
                        kRestartIndex};  // last, second-last, third-last
    int64_t leaves = 0, culled = 0;
    int strips = 0;

    template <typename Emit>
    void place(const Refiner::Chunk& ch, Emit&& emit) {
        leaves += ch.leaves;
        culled += ch.culled;
        const uint32_t* src = ch.buffer.data() + ch.offset;
        for (size_t s = 0; s < ch.starts.size(); ++s) {
            const int64_t begin = ch.starts[s];
            const int64_t end = s + 1 < ch.starts.size() ? int64_t(ch.starts[s + 1]) - 1 : ch.used;
            int64_t k0 = 0;  // first non-degenerate triangle, relative to begin
            const int64_t g = firstTriangle(src + begin, end - begin, side, &k0);
            if (g == 0) continue;  // nothing drawn
            bool merge = false;
            if (pos - stripStart >= 3 && tail[0] == src[begin]) {
                int shared = 0;
                for (int x = 0; x < 3; ++x)
                    for (int y = 0; y < 3; ++y) shared += tail[x] == src[begin + k0 + y];
                merge = shared == 2;
            }
            // decoded clockwise iff (g > 0) == (position odd)
            const int64_t want = g > 0 ? 1 : 0;
            int64_t drop;
            bool restart = false;
            if (merge) {
                const int64_t p0 = pos - stripStart;  // where src[begin + drop] lands
                drop = ((p0 + k0 - 1) & 1) == want ? 1 : 0;
            } else {
                if (pos != 0) restart = true, ++pos;
                stripStart = pos;
                drop = (k0 & 1) == want ? 0 : 1;
                ++strips;
            }
            const uint32_t* from = src + begin + drop;
            const int64_t length = end - begin - drop;
            // the tail first: emit may move the strip over its source
            if (length >= 3) {
                tail[0] = from[length - 1], tail[1] = from[length - 2], tail[2] = from[length - 3];
            } else {
                for (int64_t k = 0; k < length; ++k)
                    tail[2] = tail[1], tail[1] = tail[0], tail[0] = from[k];
            }
            emit(Refiner::Copy{from, length, pos, restart});
            pos += length;
        }
    }
};

inline void copyStrip(uint32_t* first, const Refiner::Copy& cp) {
    if (cp.restart) first[cp.dst - 1] = kRestartIndex;
    std::memcpy(first + cp.dst, cp.src, size_t(cp.length) * sizeof(uint32_t));
}

}  // namespace sierra::sbt
