#include "terrain/Npz.h"

#include <sierra/core/Error.h>

#include <zlib.h>

#include <array>
#include <cstring>

namespace sierra::terrain {

namespace {

uint32_t read16(const std::vector<uint8_t>& b, size_t at) {
    return uint32_t(b[at]) | uint32_t(b[at + 1]) << 8;
}
uint32_t read32(const std::vector<uint8_t>& b, size_t at) {
    return read16(b, at) | read16(b, at + 2) << 16;
}

uint32_t crc32(const uint8_t* data, size_t size) {
    static const std::array<uint32_t, 256> table = [] {
        std::array<uint32_t, 256> t{};
        for (uint32_t n = 0; n < 256; ++n) {
            uint32_t c = n;
            for (int k = 0; k < 8; ++k) c = c & 1 ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            t[n] = c;
        }
        return t;
    }();
    uint32_t c = 0xFFFFFFFFu;
    for (size_t k = 0; k < size; ++k) c = table[(c ^ data[k]) & 0xFF] ^ (c >> 8);
    return c ^ 0xFFFFFFFFu;
}

// Number of dimensions in an .npy header's shape tuple, -1 if unreadable.
int npyDimensions(const std::vector<uint8_t>& npy) {
    if (npy.size() < 12 || std::memcmp(npy.data(), "\x93NUMPY", 6) != 0) return -1;
    std::string header(npy.begin() + 8, npy.begin() + std::min<size_t>(npy.size(), 8 + 4096));
    size_t shape = header.find("'shape'");
    size_t open = header.find('(', shape), close = header.find(')', open);
    if (shape == std::string::npos || open == std::string::npos || close == std::string::npos)
        return -1;
    int dims = 0;
    bool inNumber = false;
    for (size_t k = open + 1; k < close; ++k) {
        bool digit = header[k] >= '0' && header[k] <= '9';
        if (digit && !inNumber) ++dims;
        inNumber = digit;
    }
    return dims;
}

struct Member {
    std::string name;
    uint32_t method = 0, crc = 0;
    uint64_t compressed = 0, size = 0, localHeader = 0;
};

Error failure(const std::string& path, const std::string& why) {
    return Error(msg(path, ": ", why));
}

// The archive's members from its zip directory.
std::vector<Member> readDirectory(const std::string& path, const std::vector<uint8_t>& bytes) {
    auto fail = [&](const std::string& why) { return failure(path, why); };
    // The end-of-central-directory record: 22 bytes, at most 64 KiB of comment after it.
    if (bytes.size() < 22) throw fail("too short for an .npz (zip) archive");
    size_t eocd = std::string::npos;
    for (size_t at = bytes.size() - 22 + 1; at-- > 0 && bytes.size() - at <= 22 + 65535;)
        if (read32(bytes, at) == 0x06054b50u) {
            eocd = at;
            break;
        }
    if (eocd == std::string::npos) throw fail("not an .npz archive (no zip directory found)");
    uint32_t count = read16(bytes, eocd + 10);
    uint64_t dirSize = read32(bytes, eocd + 12), dirOffset = read32(bytes, eocd + 16);
    if (count == 0xFFFF || dirOffset == 0xFFFFFFFFu)
        throw fail("zip64 .npz archives are not supported");
    if (dirOffset + dirSize > eocd) throw fail("corrupt .npz: its directory lies outside the file");

    std::vector<Member> members;
    size_t at = size_t(dirOffset);
    for (uint32_t k = 0; k < count; ++k) {
        if (at + 46 > eocd || read32(bytes, at) != 0x02014b50u)
            throw fail("corrupt .npz directory entry");
        Member m;
        uint32_t flags = read16(bytes, at + 8);
        m.method = read16(bytes, at + 10);
        m.crc = read32(bytes, at + 16);
        m.compressed = read32(bytes, at + 20);
        m.size = read32(bytes, at + 24);
        uint32_t nameLength = read16(bytes, at + 28), extra = read16(bytes, at + 30),
                 comment = read16(bytes, at + 32);
        m.localHeader = read32(bytes, at + 42);
        if (at + 46 + nameLength > eocd) throw fail("corrupt .npz directory entry");
        m.name.assign(reinterpret_cast<const char*>(&bytes[at + 46]), nameLength);
        if (flags & 1) throw fail(msg("member ", m.name, " is encrypted"));
        if (m.size == 0xFFFFFFFFu || m.compressed == 0xFFFFFFFFu)
            throw fail("zip64 .npz archives are not supported");
        members.push_back(m);
        at += 46 + nameLength + extra + comment;
    }
    return members;
}

// The inflated bytes of member `m`, at most maxBytes, CRC checked.
std::vector<uint8_t> extract(const std::string& path, const std::vector<uint8_t>& bytes,
                             const Member& m, uint64_t maxBytes) {
    auto fail = [&](const std::string& why) { return failure(path, why); };
    if (m.method != 0 && m.method != 8)
        throw fail(msg("member ", m.name, " uses zip method ", m.method,
                       "; .npz members are stored or deflated"));
    if (m.size > maxBytes)
        throw fail(
            msg("member ", m.name, " holds ", m.size, " bytes, over the limit of ", maxBytes));
    // Deflate expands at most 1032:1, so a small member claiming a huge size
    // is refused before its buffer is allocated.
    if (m.size > m.compressed * 1032 + 1024)
        throw fail(msg("member ", m.name, " claims ", m.size, " bytes from ", m.compressed,
                       " compressed, more than deflate can expand"));
    size_t local = size_t(m.localHeader);
    if (local + 30 > bytes.size() || read32(bytes, local) != 0x04034b50u)
        throw fail(msg("corrupt .npz: no local header for ", m.name));
    size_t data = local + 30 + read16(bytes, local + 26) + read16(bytes, local + 28);
    if (data + m.compressed > bytes.size())
        throw fail(msg("truncated .npz: member ", m.name, " is cut short"));
    std::vector<uint8_t> out(size_t(m.size));
    if (m.method == 0) {
        if (m.compressed != m.size)
            throw fail(msg("corrupt .npz: stored member ", m.name, " changes size"));
        // An empty member has no data to copy (and out.data() may be null).
        if (!out.empty()) std::memcpy(out.data(), bytes.data() + data, out.size());
    } else {
        // Raw deflate (no zlib header) into a buffer of exactly the declared size.
        z_stream z{};
        if (inflateInit2(&z, -MAX_WBITS) != Z_OK) throw fail("cannot start zlib's inflate");
        z.next_in = const_cast<Bytef*>(bytes.data() + data);
        z.avail_in = uInt(m.compressed);
        z.next_out = out.data();
        z.avail_out = uInt(out.size());
        int rc = inflate(&z, Z_FINISH);
        uint64_t produced = z.total_out;
        inflateEnd(&z);
        if (rc != Z_STREAM_END || produced != m.size)
            throw fail(msg("member ", m.name, " does not inflate to its declared size (",
                           rc == Z_STREAM_END ? "size differs" : "corrupt deflate data", ")"));
    }
    if (crc32(out.data(), out.size()) != m.crc)
        throw fail(msg("member ", m.name, " fails its CRC check"));
    return out;
}

}  // namespace

std::vector<uint8_t> npzMember(const std::string& path, const std::vector<uint8_t>& bytes,
                               const std::string& member, uint64_t maxBytes) {
    auto fail = [&](const std::string& why) { return failure(path, why); };
    const std::vector<Member> members = readDirectory(path, bytes);
    std::string names;
    for (const Member& m : members) {
        names += (names.empty() ? "" : ", ") + m.name;
        if (!member.empty()) {
            if (m.name == member || m.name == member + ".npy")
                return extract(path, bytes, m, maxBytes);
            continue;
        }
        if (m.size > maxBytes || !m.name.ends_with(".npy")) continue;
        std::vector<uint8_t> npy = extract(path, bytes, m, maxBytes);
        if (npyDimensions(npy) == 2) return npy;
    }
    if (!member.empty()) throw fail(msg("no member '", member, "' (members: ", names, ")"));
    throw fail(msg("no 2-D array among the members (", names, ")"));
}

std::map<std::string, std::vector<uint8_t>> npzSmallMembers(const std::string& path,
                                                            const std::vector<uint8_t>& bytes,
                                                            uint64_t maxBytes) {
    std::map<std::string, std::vector<uint8_t>> out;
    for (const Member& m : readDirectory(path, bytes))
        if (m.name.ends_with(".npy") && m.size <= maxBytes)
            out[m.name.substr(0, m.name.size() - 4)] = extract(path, bytes, m, maxBytes);
    return out;
}

}  // namespace sierra::terrain
