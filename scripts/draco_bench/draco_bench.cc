// Same-run Draco baseline for lrmesh's Edgebreaker decode (not part of CI; see
// scripts/draco-compare.sh and scripts/geometry-compare.sh). For one .drc file, prints one
// line of key=value pairs: faces, points, bytes (the file's size), conn_bytes (the bytes
// before the attribute data: header and connectivity), conn_bpt, conn_mtps (median M
// triangles/s of a decode that stops after the connectivity: attribute decoding is skipped),
// full_mtps (median M triangles/s of the whole decode) and arrays_mtps (median M triangles/s
// of the whole decode followed by copying the faces into a u32 array and every attribute's
// values, per point, into f32 arrays: what a loader does, e.g. three.js's DRACOLoader with
// GetAttributeFloatForAllPoints).
//
// With SOURCE and QP as well (the mesh file draco_encoder read, and its -qp), it also times
// the library's encode with draco_encoder's settings for `-cl 10 -qp QP` (Encoder, speed 0,
// positions QP bits, 0 for none; texture coordinates 10, normals 8, generic 8 bits, as the
// tool's defaults) on the mesh as Draco's reader loads it, and prints enc_bytes (which must
// be the file's size when the file came from that command) and enc_mtps (median).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <memory>
#include <vector>

#include "draco/compression/decode.h"
#include "draco/compression/encode.h"
#include "draco/compression/mesh/mesh_edgebreaker_decoder.h"
#include "draco/io/mesh_io.h"

namespace {

// Edgebreaker decoder that decodes the connectivity only, and records how many bytes the
// connectivity took.
class ConnectivityOnly : public draco::MeshEdgebreakerDecoder {
 public:
  // Input size; the connectivity decoder repositions the buffer, so what it consumed is
  // measured as what is left for the attributes.
  int64_t total = 0;
  int64_t conn_bytes = 0;

 protected:
  bool DecodeConnectivity() override {
    const bool ok = draco::MeshEdgebreakerDecoder::DecodeConnectivity();
    conn_bytes = total - buffer()->remaining_size();
    return ok;
  }
  bool DecodePointAttributes() override { return true; }
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// The decoded mesh as arrays: three point ids per face, and each attribute's values per
// point as f32.
struct Arrays {
  std::vector<uint32_t> faces;
  std::vector<std::vector<float>> attributes;
};

Arrays to_arrays(const draco::Mesh &mesh) {
  Arrays out;
  out.faces.resize(3 * static_cast<size_t>(mesh.num_faces()));
  for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f) {
    const auto &face = mesh.face(f);
    for (int k = 0; k < 3; ++k) out.faces[3 * f.value() + k] = face[k].value();
  }
  const size_t n = mesh.num_points();
  for (int a = 0; a < mesh.num_attributes(); ++a) {
    const draco::PointAttribute *att = mesh.attribute(a);
    const int c = att->num_components();
    std::vector<float> values(n * c);
    for (draco::PointIndex p(0); p < mesh.num_points(); ++p) {
      att->ConvertValue<float>(att->mapped_index(p), c, &values[p.value() * c]);
    }
    out.attributes.push_back(std::move(values));
  }
  return out;
}

}  // namespace

int main(int argc, char **argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s FILE.drc [RUNS [SOURCE QP]]\n", argv[0]);
    return 2;
  }
  const int runs = argc > 2 ? std::atoi(argv[2]) : 21;
  std::ifstream in(argv[1], std::ios::binary);
  std::vector<char> data((std::istreambuf_iterator<char>(in)),
                         std::istreambuf_iterator<char>());
  if (data.empty()) {
    std::fprintf(stderr, "cannot read %s\n", argv[1]);
    return 1;
  }
  using clock = std::chrono::steady_clock;
  std::vector<double> conn, full, arrays;
  int64_t faces = 0, points = 0, conn_bytes = 0;
  for (int i = 0; i < runs; ++i) {
    {
      draco::DecoderBuffer buf;
      buf.Init(data.data(), data.size());
      draco::DecoderOptions options;
      draco::Mesh mesh;
      ConnectivityOnly dec;
      dec.total = static_cast<int64_t>(data.size());
      const auto t0 = clock::now();
      const draco::Status s = dec.Decode(options, &buf, &mesh);
      const auto t1 = clock::now();
      if (!s.ok()) {
        std::fprintf(stderr, "draco connectivity decode failed: %s\n",
                     s.error_msg());
        return 1;
      }
      faces = mesh.num_faces();
      conn_bytes = dec.conn_bytes;
      conn.push_back(std::chrono::duration<double>(t1 - t0).count());
    }
    {
      draco::DecoderBuffer buf;
      buf.Init(data.data(), data.size());
      draco::Decoder dec;
      const auto t0 = clock::now();
      auto mesh = dec.DecodeMeshFromBuffer(&buf);
      const auto t1 = clock::now();
      if (!mesh.ok() || mesh.value()->num_faces() != faces) {
        std::fprintf(stderr, "draco full decode failed\n");
        return 1;
      }
      full.push_back(std::chrono::duration<double>(t1 - t0).count());
    }
    {
      draco::DecoderBuffer buf;
      buf.Init(data.data(), data.size());
      draco::Decoder dec;
      const auto t0 = clock::now();
      auto mesh = dec.DecodeMeshFromBuffer(&buf);
      if (!mesh.ok()) {
        std::fprintf(stderr, "draco full decode failed\n");
        return 1;
      }
      const Arrays out = to_arrays(*mesh.value());
      const auto t1 = clock::now();
      if (static_cast<int64_t>(out.faces.size()) != 3 * faces) {
        std::fprintf(stderr, "draco arrays decode failed\n");
        return 1;
      }
      points = mesh.value()->num_points();
      arrays.push_back(std::chrono::duration<double>(t1 - t0).count());
    }
  }
  std::printf(
      "faces=%lld points=%lld bytes=%lld conn_bytes=%lld conn_bpt=%.3f conn_mtps=%.1f "
      "full_mtps=%.1f arrays_mtps=%.2f",
      (long long)faces, (long long)points, (long long)data.size(),
      (long long)conn_bytes, 8.0 * conn_bytes / faces, faces / median(conn) / 1e6,
      faces / median(full) / 1e6, faces / median(arrays) / 1e6);
  if (argc > 4) {
    // Encode as draco_encoder -cl 10 -qp QP does, from the mesh as its reader loads it.
    auto loaded = draco::ReadMeshFromFile(argv[3]);
    if (!loaded.ok()) {
      std::fprintf(stderr, "\ncannot read %s: %s\n", argv[3], loaded.status().error_msg());
      return 1;
    }
    const draco::Mesh &source = *loaded.value();
    const int qp = std::atoi(argv[4]);
    draco::Encoder encoder;
    if (qp > 0) encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, qp);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 10);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 8);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::GENERIC, 8);
    encoder.SetSpeedOptions(0, 0);  // 10 - compression level 10
    std::vector<double> enc;
    size_t enc_bytes = 0;
    for (int i = 0; i < runs; ++i) {
      draco::EncoderBuffer out;
      const auto t0 = clock::now();
      const draco::Status s = encoder.EncodeMeshToBuffer(source, &out);
      const auto t1 = clock::now();
      if (!s.ok()) {
        std::fprintf(stderr, "\ndraco encode failed: %s\n", s.error_msg());
        return 1;
      }
      enc_bytes = out.size();
      enc.push_back(std::chrono::duration<double>(t1 - t0).count());
    }
    std::printf(" enc_bytes=%zu enc_mtps=%.2f", enc_bytes, source.num_faces() / median(enc) / 1e6);
  }
  std::printf("\n");
  return 0;
}
