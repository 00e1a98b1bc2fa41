#include "common/mcap/compression.hpp"

#include <algorithm>

#include <zstd.h>

namespace fsd::mcap {

const char* to_string(Compression c) { return c == Compression::Zstd ? "zstd" : ""; }

struct ZstdCompressor::Impl {
  ZSTD_CCtx* cctx = ZSTD_createCCtx();
};

// Created with the first zstd chunk: a reader of uncompressed files never pays for it.
struct ChunkDecompressor::Impl {
  ZSTD_DCtx* dctx = nullptr;
};

ChunkDecompressor::ChunkDecompressor() : impl_(std::make_unique<Impl>()) {}

ChunkDecompressor::~ChunkDecompressor() { ZSTD_freeDCtx(impl_->dctx); }

ZstdCompressor::ZstdCompressor(int level) : impl_(std::make_unique<Impl>()) {
  if (!impl_->cctx) throw McapError("zstd: cannot create a compression context");
  ZSTD_CCtx_setParameter(impl_->cctx, ZSTD_c_compressionLevel, level);
  // The frame states its content size, so a reader can check it against the chunk's uncompressed_size.
  ZSTD_CCtx_setParameter(impl_->cctx, ZSTD_c_contentSizeFlag, 1);
}

ZstdCompressor::~ZstdCompressor() { ZSTD_freeCCtx(impl_->cctx); }

void ZstdCompressor::compress(std::span<const std::uint8_t> in, Bytes& out) {
  out.resize(ZSTD_compressBound(in.size()));
  const std::size_t n = ZSTD_compress2(impl_->cctx, out.data(), out.size(), in.data(), in.size());
  if (ZSTD_isError(n)) throw McapError(std::string("zstd compression failed: ") + ZSTD_getErrorName(n));
  out.resize(n);
}

std::string ChunkDecompressor::decompress(const std::string& compression, std::span<const std::uint8_t> in,
                                          std::uint64_t uncompressed_size, Bytes& out) {
  if (compression.empty()) {
    if (in.size() != uncompressed_size) return "uncompressed chunk whose size differs from its uncompressed_size";
    out.assign(in.begin(), in.end());
    return "";
  }
  if (compression != "zstd") return "compression '" + compression + "' is not supported (only none and zstd)";
  // A frame that states its size must state the chunk's: this rejects a lying size before allocating for it.
  const unsigned long long stated = ZSTD_getFrameContentSize(in.data(), in.size());
  if (stated == ZSTD_CONTENTSIZE_ERROR) return "damaged zstd data";
  if (stated != ZSTD_CONTENTSIZE_UNKNOWN && stated != uncompressed_size)
    return "zstd frame size differs from the chunk's uncompressed_size";
  if (!impl_->dctx && !(impl_->dctx = ZSTD_createDCtx())) return "zstd: cannot create a decompression context";
  // Streamed in steps, so memory follows what the data really decompresses to, never a size field alone.
  ZSTD_DCtx_reset(impl_->dctx, ZSTD_reset_session_only);
  ZSTD_inBuffer src{in.data(), in.size(), 0};
  std::size_t produced = 0;
  std::uint8_t probe = 0;
  out.clear();
  for (;;) {
    const std::size_t step = static_cast<std::size_t>(std::min<std::uint64_t>(uncompressed_size - produced, 1 << 17));
    ZSTD_outBuffer dst{&probe, 1, 0};  // with the chunk full: any further byte is one too many
    if (step > 0) {
      out.resize(produced + step);
      dst = ZSTD_outBuffer{out.data() + produced, step, 0};
    }
    const std::size_t src_before = src.pos;
    const std::size_t ret = ZSTD_decompressStream(impl_->dctx, &dst, &src);
    if (ZSTD_isError(ret)) return std::string("damaged zstd data (") + ZSTD_getErrorName(ret) + ")";
    if (step == 0 && dst.pos > 0) return "zstd data decompresses to more than the chunk's uncompressed_size";
    produced += step > 0 ? dst.pos : 0;
    out.resize(produced);
    if (ret == 0 && src.pos == src.size) break;  // every frame finished, all input used
    if (dst.pos == 0 && src.pos == src_before) return "zstd data ends inside a frame";
  }
  if (produced != uncompressed_size) return "zstd data decompresses to less than the chunk's uncompressed_size";
  return "";
}

}  // namespace fsd::mcap
