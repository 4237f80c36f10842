// meshoptimizer's own codec as a size baseline for scripts/geometry-compare.sh (not part of
// CI): positions and triangles only, no gzip.
//
// usage: meshopt_bench MESH.ply BITS [RUNS [OUT.bin]]
//
// Reads a binary little-endian PLY with float x, y, z per vertex and a face list (what
// `lrmesh convert` writes; polygons are fan-triangulated). BITS = 1..16: positions on a grid of
// BITS bits per coordinate in the bounding cube (the side is the box's largest extent, step
// side / (2^BITS - 1), as Draco's -qp and lrmesh's --quantize-position), stored as 4 x u16
// (x, y, z, 0): meshopt_encodeVertexBuffer takes vertex sizes that are multiples of 4, and
// gltfpack pads 16-bit positions the same way; BITS = 17..30: 3 x u32. BITS = 0: the f32s as
// they are (lossless, 12 bytes per vertex). Then meshopt_optimizeVertexCache,
// meshopt_optimizeVertexFetch (reorders the vertices), meshopt_encodeIndexBuffer (version 1)
// and meshopt_encodeVertexBuffer (version 0, the only one of meshoptimizer 0.18).
//
// Prints one line of key=value pairs: faces, vertices, side (the bounding box's largest
// extent), index_bytes, vertex_bytes, bytes (the sum), max_err (largest coordinate error, in
// units of the box's largest extent) and dec_mtps (median M triangles/s of
// meshopt_decodeIndexBuffer + meshopt_decodeVertexBuffer into arrays, without dequantizing).
// With OUT.bin, writes the two encoded buffers there, one after the other, for a
// general-purpose compressor to be tried on.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <meshoptimizer.h>

namespace {

struct Mesh {
  std::vector<float> positions;  // 3 per vertex
  std::vector<uint32_t> indices;  // 3 per triangle
};

[[noreturn]] void fail(const std::string &what) {
  std::fprintf(stderr, "meshopt_bench: %s\n", what.c_str());
  std::exit(1);
}

size_t type_size(const std::string &t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" ||
      t == "float32")
    return 4;
  if (t == "double" || t == "float64") return 8;
  fail("unknown PLY type " + t);
}

uint64_t read_uint(const unsigned char *p, const std::string &t) {
  switch (type_size(t)) {
    case 1: return p[0];
    case 2: { uint16_t v; std::memcpy(&v, p, 2); return v; }
    case 4: { uint32_t v; std::memcpy(&v, p, 4); return v; }
    default: fail("bad index type " + t);
  }
}

// A binary little-endian PLY: vertex x, y, z as float (other vertex properties of fixed size
// skipped), faces as one list property.
Mesh read_ply(const char *path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<unsigned char> data((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
  const std::string text(data.begin(), data.end());
  const size_t end = text.find("end_header\n");
  if (text.rfind("ply\n", 0) != 0 || end == std::string::npos) fail("not a PLY file");
  std::istringstream header(text.substr(0, end));
  std::string line, element;
  size_t nv = 0, nf = 0, vstride = 0;
  int xyz[3] = {-1, -1, -1};
  std::string count_type, index_type;
  while (std::getline(header, line)) {
    std::istringstream w(line);
    std::string key;
    w >> key;
    if (key == "format") {
      std::string f;
      w >> f;
      if (f != "binary_little_endian") fail("only binary little-endian PLY is read");
    } else if (key == "element") {
      size_t n;
      w >> element >> n;
      if (element == "vertex") nv = n;
      else if (element == "face") nf = n;
      else if (n) fail("unexpected element " + element);
    } else if (key == "property") {
      std::string type, name;
      w >> type;
      if (element == "vertex") {
        w >> name;
        if (type == "list") fail("list property in vertex");
        for (int k = 0; k < 3; ++k)
          if (name == std::string(1, "xyz"[k])) {
            if (type != "float" && type != "float32") fail("positions must be float");
            xyz[k] = static_cast<int>(vstride);
          }
        vstride += type_size(type);
      } else if (element == "face") {
        if (type != "list") fail("face property must be a list");
        w >> count_type >> index_type;
      }
    }
  }
  if (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0) fail("no x, y, z");
  const unsigned char *p = data.data() + end + 11, *stop = data.data() + data.size();
  Mesh m;
  if (static_cast<size_t>(stop - p) < nv * vstride) fail("truncated vertices");
  m.positions.resize(3 * nv);
  for (size_t v = 0; v < nv; ++v, p += vstride)
    for (int k = 0; k < 3; ++k) std::memcpy(&m.positions[3 * v + k], p + xyz[k], 4);
  const size_t cs = type_size(count_type), is = type_size(index_type);
  for (size_t f = 0; f < nf; ++f) {
    if (stop - p < static_cast<ptrdiff_t>(cs)) fail("truncated faces");
    const size_t n = read_uint(p, count_type);
    p += cs;
    if (static_cast<size_t>(stop - p) < n * is) fail("truncated faces");
    std::vector<uint32_t> poly(n);
    for (size_t k = 0; k < n; ++k, p += is) {
      poly[k] = static_cast<uint32_t>(read_uint(p, index_type));
      if (poly[k] >= nv) fail("index out of range");
    }
    for (size_t k = 2; k < n; ++k) {
      m.indices.push_back(poly[0]);
      m.indices.push_back(poly[k - 1]);
      m.indices.push_back(poly[k]);
    }
  }
  return m;
}

// Whether `b` holds the triangles of `a` in the same order, each maybe rotated (the index
// codec may rotate a triangle's corners).
bool same_triangles(const std::vector<uint32_t> &a, const std::vector<uint32_t> &b) {
  if (a.size() != b.size()) return false;
  for (size_t t = 0; t + 2 < a.size(); t += 3) {
    bool ok = false;
    for (int r = 0; r < 3 && !ok; ++r)
      ok = a[t] == b[t + r] && a[t + 1] == b[t + (r + 1) % 3] && a[t + 2] == b[t + (r + 2) % 3];
    if (!ok) return false;
  }
  return true;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char **argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s MESH.ply BITS [RUNS [OUT.bin]]\n", argv[0]);
    return 2;
  }
  const Mesh mesh = read_ply(argv[1]);
  const int bits = std::atoi(argv[2]);
  const int runs = argc > 3 ? std::max(1, std::atoi(argv[3])) : 11;
  if (bits < 0 || bits > 30) fail("BITS must be 0 to 30");
  const size_t nv = mesh.positions.size() / 3, ni = mesh.indices.size();

  // The vertices as stored: f32, 4 x u16 or 3 x u32.
  const size_t vsize = bits == 0 ? 12 : bits <= 16 ? 8 : 12;
  std::vector<unsigned char> vertices(nv * vsize, 0);
  float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0}, side = 0;
  for (int k = 0; k < 3; ++k) {
    lo[k] = hi[k] = nv ? mesh.positions[k] : 0;
    for (size_t v = 0; v < nv; ++v) {
      lo[k] = std::min(lo[k], mesh.positions[3 * v + k]);
      hi[k] = std::max(hi[k], mesh.positions[3 * v + k]);
    }
    side = std::max(side, hi[k] - lo[k]);
  }
  const double max_level = bits ? std::ldexp(1.0, bits) - 1 : 0;
  if (bits == 0) {
    std::memcpy(vertices.data(), mesh.positions.data(), nv * 12);
  } else {
    for (size_t v = 0; v < nv; ++v)
      for (int k = 0; k < 3; ++k) {
        const double x = mesh.positions[3 * v + k];
        const double q = side > 0 ? std::round((x - lo[k]) / side * max_level) : 0;
        const uint32_t level = static_cast<uint32_t>(std::clamp(q, 0.0, max_level));
        if (bits <= 16) {
          const uint16_t l16 = static_cast<uint16_t>(level);
          std::memcpy(&vertices[v * vsize + 2 * k], &l16, 2);
        } else {
          std::memcpy(&vertices[v * vsize + 4 * k], &level, 4);
        }
      }
  }

  std::vector<uint32_t> indices(ni);
  meshopt_optimizeVertexCache(indices.data(), mesh.indices.data(), ni, nv);
  std::vector<unsigned char> fetched(nv * vsize);
  const size_t used =
      meshopt_optimizeVertexFetch(fetched.data(), indices.data(), ni, vertices.data(), nv, vsize);
  fetched.resize(used * vsize);

  meshopt_encodeIndexVersion(1);
  std::vector<unsigned char> ib(meshopt_encodeIndexBufferBound(ni, used));
  ib.resize(meshopt_encodeIndexBuffer(ib.data(), ib.size(), indices.data(), ni));
  std::vector<unsigned char> vb(meshopt_encodeVertexBufferBound(used, vsize));
  vb.resize(meshopt_encodeVertexBuffer(vb.data(), vb.size(), fetched.data(), used, vsize));

  // The error of the grid, against the f32 positions (through the fetch remap, by value).
  double max_err = 0;
  if (bits && side > 0) {
    for (size_t v = 0; v < nv; ++v)
      for (int k = 0; k < 3; ++k) {
        uint32_t level = 0;
        if (bits <= 16) {
          uint16_t l16;
          std::memcpy(&l16, &vertices[v * vsize + 2 * k], 2);
          level = l16;
        } else {
          std::memcpy(&level, &vertices[v * vsize + 4 * k], 4);
        }
        const double back = lo[k] + level / max_level * side;
        max_err = std::max(max_err, std::fabs(back - mesh.positions[3 * v + k]) / side);
      }
  }

  // Decode to arrays, checked once against what was encoded.
  using clock = std::chrono::steady_clock;
  std::vector<double> times;
  std::vector<uint32_t> di(ni);
  std::vector<unsigned char> dv(used * vsize);
  for (int i = 0; i < runs; ++i) {
    const auto t0 = clock::now();
    const int a = meshopt_decodeIndexBuffer(di.data(), ni, 4, ib.data(), ib.size());
    const int b = meshopt_decodeVertexBuffer(dv.data(), used, vsize, vb.data(), vb.size());
    const auto t1 = clock::now();
    if (a || b || (i == 0 && (!same_triangles(indices, di) || dv != fetched)))
      fail("decode does not give back the input");
    times.push_back(std::chrono::duration<double>(t1 - t0).count());
  }

  if (argc > 4) {
    std::ofstream out(argv[4], std::ios::binary);
    out.write(reinterpret_cast<const char *>(ib.data()), ib.size());
    out.write(reinterpret_cast<const char *>(vb.data()), vb.size());
  }
  const size_t faces = ni / 3;
  std::printf(
      "faces=%zu vertices=%zu side=%.9g index_bytes=%zu vertex_bytes=%zu bytes=%zu max_err=%.3g "
      "dec_mtps=%.1f\n",
      faces, used, static_cast<double>(side), ib.size(), vb.size(), ib.size() + vb.size(), max_err,
      faces / median(times) / 1e6);
  return 0;
}
