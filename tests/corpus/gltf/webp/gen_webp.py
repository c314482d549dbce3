#!/usr/bin/env python3
"""Generates the texture-source extension scenes from features/box_plain.gltf (the 16x16 checker
box): its PNG is re-encoded as lossless WebP (Pillow, which Debian builds with libwebp: run with
/usr/bin/python3 and python3-pil), so the WebP files must draw exactly the PNG's pixels. The output
is committed; the tests need no encoder. Run: `/usr/bin/python3 tests/corpus/gltf/webp/gen_webp.py`.

  box_webp.gltf           EXT_texture_webp in extensionsUsed: textures[0].extensions.EXT_texture_webp
                          .source = images[0] (the WebP checker); its core source is images[1], a
                          2x2 magenta PNG fallback that a WebP-capable viewer does not draw.
  box_webp_required.gltf  EXT_texture_webp in extensionsRequired; no core source, one WebP image
                          (in a bufferView, mimeType image/webp).
  box_basisu.gltf         KHR_texture_basisu in extensionsUsed: textures[0].extensions.
                          KHR_texture_basisu.source = images[1], 64 bytes that start like a KTX2
                          file (not decodable here); the core source images[0] is the checker PNG,
                          which must be drawn, with one warning line.
The MANIFEST corpus (gen_corpus.py) holds the refusals: a truncated WebP, a basisu texture without
a fallback, a WebP source out of range.
"""
import base64
import copy
import io
import json
import os

from PIL import Image

HERE = os.path.dirname(os.path.abspath(__file__))
PLAIN = os.path.join(HERE, "..", "features", "box_plain.gltf")


def data_uri(mime, data):
    return "data:%s;base64,%s" % (mime, base64.b64encode(data).decode())


def png_of(uri):
    return base64.b64decode(uri.split(",", 1)[1])


def webp_lossless(png):
    im = Image.open(io.BytesIO(png)).convert("RGBA")
    out = io.BytesIO()
    im.save(out, "WEBP", lossless=True, exact=True, quality=100, method=6)
    data = out.getvalue()
    back = Image.open(io.BytesIO(data)).convert("RGBA")
    assert back.tobytes() == im.tobytes(), "lossless WebP does not round-trip"
    return data


def magenta_png():
    out = io.BytesIO()
    Image.new("RGBA", (2, 2), (255, 0, 255, 255)).save(out, "PNG")
    return out.getvalue()


def write(name, doc):
    doc["asset"]["generator"] = "passgraph gen_webp.py"
    with open(os.path.join(HERE, name), "w") as f:
        f.write(json.dumps(doc, indent=1) + "\n")


def main():
    base = json.load(open(PLAIN))
    png = png_of(base["images"][0]["uri"])
    webp = webp_lossless(png)

    d = copy.deepcopy(base)
    d["extensionsUsed"] = ["EXT_texture_webp"]
    d["images"] = [{"uri": data_uri("image/webp", webp)}, {"uri": data_uri("image/png", magenta_png())}]
    d["textures"] = [{"source": 1, "sampler": 0, "extensions": {"EXT_texture_webp": {"source": 0}}}]
    write("box_webp.gltf", d)

    d = copy.deepcopy(base)
    d["extensionsUsed"] = d["extensionsRequired"] = ["EXT_texture_webp"]
    buf = base64.b64decode(d["buffers"][0]["uri"].split(",", 1)[1])
    off = len(buf) + (-len(buf)) % 4
    buf = buf + b"\0" * (off - len(buf)) + webp
    d["bufferViews"].append({"buffer": 0, "byteOffset": off, "byteLength": len(webp)})
    d["buffers"][0] = {"byteLength": len(buf), "uri": data_uri("application/octet-stream", buf)}
    d["images"] = [{"bufferView": len(d["bufferViews"]) - 1, "mimeType": "image/webp"}]
    d["textures"] = [{"sampler": 0, "extensions": {"EXT_texture_webp": {"source": 0}}}]
    write("box_webp_required.gltf", d)

    d = copy.deepcopy(base)
    d["extensionsUsed"] = ["KHR_texture_basisu"]
    ktx2 = bytes([0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A]) + bytes(52)
    d["images"].append({"uri": data_uri("image/ktx2", ktx2)})
    d["textures"] = [{"source": 0, "sampler": 0, "extensions": {"KHR_texture_basisu": {"source": 1}}}]
    write("box_basisu.gltf", d)
    print("wrote box_webp.gltf, box_webp_required.gltf, box_basisu.gltf (WebP %d bytes)" % len(webp))


if __name__ == "__main__":
    main()
