// JPEG decoding through libjpeg-turbo (see JpegFile.h).
#include "image/JpegFile.h"

#include <jpeglib.h>
#include <cstdio>  // jpeglib.h needs FILE and size_t declared first

#include <csetjmp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace preskin::image {

namespace {

// libjpeg's error manager extended with the jump back and the message; nothing is printed.
struct JpegErrors {
    jpeg_error_mgr manager;
    std::jmp_buf jump;
    char message[JMSG_LENGTH_MAX];
};

void jpegErrorExit(j_common_ptr info) {
    auto* errors = reinterpret_cast<JpegErrors*>(info->err);
    info->err->format_message(info, errors->message);
    std::longjmp(errors->jump, 1);
}
// Corrupt-data warnings ("premature end of data segment") are errors here: the image would be
// partly grey.
void jpegEmitMessage(j_common_ptr info, int level) {
    if (level < 0) jpegErrorExit(info);
}

// The part libjpeg may leave by longjmp: only caller-owned objects are touched, so no destructor
// is skipped.
bool readJpeg(jpeg_decompress_struct& info, JpegErrors& errors, std::span<const uint8_t> bytes,
              const SizeLimits& limits, PixelImage& out, std::vector<uint8_t>& row,
              std::optional<std::string>& sizeProblem) {
    if (setjmp(errors.jump)) return false;
    jpeg_create_decompress(&info);
    jpeg_mem_src(&info, bytes.data(), static_cast<unsigned long>(bytes.size()));
    jpeg_read_header(&info, TRUE);
    try {
        checkImageSize(info.image_width, info.image_height, limits);
    } catch (const std::exception& e) {
        sizeProblem = e.what();
        return false;
    }
    const bool cmyk = info.jpeg_color_space == JCS_CMYK || info.jpeg_color_space == JCS_YCCK;
    const bool grey = info.jpeg_color_space == JCS_GRAYSCALE;
    info.out_color_space = cmyk ? JCS_CMYK : grey ? JCS_GRAYSCALE : JCS_RGB;
    jpeg_start_decompress(&info);
    const uint32_t components = static_cast<uint32_t>(info.output_components);
    out.width = info.output_width;
    out.height = info.output_height;
    out.channels = grey ? 1 : 3;
    auto& texels = out.texels.emplace<std::vector<uint8_t>>(out.valueCount());
    row.resize(size_t(out.width) * components);
    while (info.output_scanline < info.output_height) {
        const size_t y = info.output_scanline;
        JSAMPROW rows[1] = {row.data()};
        jpeg_read_scanlines(&info, rows, 1);
        uint8_t* dst = texels.data() + y * out.width * out.channels;
        if (!cmyk) {
            std::copy(row.begin(), row.end(), dst);
            continue;
        }
        // Adobe writes CMYK inverted (255 = no ink): R = C' K' / 255 with C', K' as stored.
        for (size_t x = 0; x < out.width; ++x) {
            const uint8_t* s = row.data() + x * 4;
            for (int c = 0; c < 3; ++c) dst[x * 3 + size_t(c)] = uint8_t((uint32_t(s[c]) * s[3] + 127) / 255);
        }
    }
    jpeg_finish_decompress(&info);
    return true;
}

}  // namespace

PixelImage decodeJpeg(std::span<const uint8_t> bytes, const SizeLimits& limits) {
    jpeg_decompress_struct info{};
    JpegErrors errors{};
    info.err = jpeg_std_error(&errors.manager);
    errors.manager.error_exit = &jpegErrorExit;
    errors.manager.emit_message = &jpegEmitMessage;
    PixelImage out;
    std::vector<uint8_t> row;
    std::optional<std::string> sizeProblem;
    const bool ok = readJpeg(info, errors, bytes, limits, out, row, sizeProblem);
    jpeg_destroy_decompress(&info);
    if (sizeProblem) throw std::runtime_error(*sizeProblem);
    if (!ok) throw std::runtime_error(std::string("cannot decode the JPEG data: ") + errors.message);
    return out;
}

}  // namespace preskin::image
