"""Loading input images: huge files at the working size, the pixel limit, pages, messages."""

from __future__ import annotations

import os
import struct
import warnings
import zlib

import cv2
import numpy as np
import pytest

from img2logo.constants import MAX_IMAGE_SIDE
from img2logo.errors import ImageNotFoundError, InvalidImageError
from img2logo.loading import DownscaleWarning, PageWarning, composite_on_white, load_image


def _shapes(h: int, w: int, alpha: bool) -> np.ndarray:
    """A BGR(A) uint8 picture: a disc, a bar, a soft-edged transparent border when ``alpha``."""
    img = np.full((h, w, 3), 255, np.uint8)
    cv2.circle(img, (w // 2, h // 2), min(h, w) // 3, (20, 60, 200), max(2, w // 60))
    cv2.rectangle(img, (w // 10, h // 10), (w // 3, h // 4), (0, 0, 0), -1)
    if not alpha:
        return img
    a = np.full((h, w), 255, np.uint8)
    a[: h // 8] = 0
    a[h // 8 : h // 8 + 40] = np.linspace(0, 255, 40, dtype=np.uint8)[:, None]
    return np.dstack([img, a])


def _reference(arr: np.ndarray, size: tuple[int, int]) -> tuple[np.ndarray, np.ndarray]:
    """What loading did before: float64 of the full image, composited, then area-resized."""
    rgb, alpha, _ = composite_on_white(arr, "ref", bgr=True)
    return cv2.resize(rgb, size, interpolation=cv2.INTER_AREA), cv2.resize(alpha, size, interpolation=cv2.INTER_AREA)


@pytest.mark.parametrize("alpha", [False, True])
def test_large_png_is_downscaled_in_integers_like_the_float_path(tmp_path, alpha):
    arr = _shapes(2600, 3100, alpha)
    path = tmp_path / "big.png"
    cv2.imwrite(str(path), arr)
    with pytest.warns(DownscaleWarning, match=r"big\.png: image is 3100x2600 px, .*downscaled to 2048x1718 px"):
        img = load_image(path)
    assert (img.width, img.height) == (2048, 1718)
    assert img.has_alpha is alpha
    rgb, a = _reference(arr, (2048, 1718))
    # Compositing and resizing in 8 bits rounds each value by at most half a grey level.
    assert np.abs(img.rgb - rgb).max() < 1.5 / 255
    assert np.abs(img.alpha - a).max() < 1.5 / 255
    assert img.scale == pytest.approx(2048 / 3100)


def test_large_jpeg_is_decoded_at_a_reduced_size(tmp_path):
    arr = _shapes(4400, 4200, False)
    path = tmp_path / "big.jpg"
    cv2.imwrite(str(path), arr, [cv2.IMWRITE_JPEG_QUALITY, 95])
    with pytest.warns(DownscaleWarning):
        img = load_image(path)
    assert max(img.width, img.height) == MAX_IMAGE_SIDE
    full = cv2.imread(str(path), cv2.IMREAD_COLOR)
    rgb, _ = _reference(full, (img.width, img.height))
    assert np.abs(img.rgb - rgb).mean() < 0.01  # the decoder's 1/2 scale, then the area resize


def _png_header_only(path, width: int, height: int) -> None:
    """A PNG that claims ``width`` x ``height`` px and holds no pixel data (a decompression bomb's header)."""

    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    ihdr = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IEND", b""))


@pytest.mark.parametrize("side", [13000, 60000])
def test_pixel_limit_refuses_a_bomb_before_decoding(tmp_path, side):
    path = tmp_path / "bomb.png"
    _png_header_only(path, side, side)
    with pytest.raises(InvalidImageError, match=r"bomb\.png: image is .*more than the limit of 150,000,000 px"):
        load_image(path)


def test_pixel_limit_is_a_parameter(tmp_path):
    path = tmp_path / "a.png"
    cv2.imwrite(str(path), _shapes(100, 100, False))
    with pytest.raises(InvalidImageError, match=r"image is 100x100 px, more than the limit of 5,000 px"):
        load_image(path, max_pixels=5000)


def test_minimum_size_is_checked_after_the_downscale(tmp_path):
    path = tmp_path / "wide.png"
    cv2.imwrite(str(path), np.tile(np.linspace(0, 255, 40000).astype(np.uint8), (20, 1)))
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # refused before any downscale warning
        with pytest.raises(
            InvalidImageError, match=r"wide\.png: image is 40000x20 px \(downscaled to 2048x1 px to fit 2048 px\)"
        ):
            load_image(path)
    arr = np.tile(np.linspace(0, 1, 40000), (20, 1))
    with pytest.raises(InvalidImageError, match=r"<array>: image is 40000x20 px \(downscaled to 2048x1 px"):
        load_image(arr)


def test_a_multi_page_file_says_it_uses_the_first_page(tmp_path):
    path = tmp_path / "pages.tif"
    first, second = _shapes(64, 64, False), np.zeros((64, 64, 3), np.uint8)
    assert cv2.imwritemulti(str(path), [first, second])
    with pytest.warns(PageWarning, match=r"pages\.tif: the file has 2 pages; only the first is used"):
        img = load_image(path)
    assert np.ptp(img.rgb) > 0.5  # the first page, not the black one


def test_not_a_regular_file_is_named_as_such(tmp_path):
    os.mkfifo(tmp_path / "pipe.png")  # no regular file, like a device: never opened (it would block)
    with pytest.raises(ImageNotFoundError, match=r"pipe\.png is not a regular file"):
        load_image(tmp_path / "pipe.png")
    with pytest.raises(ImageNotFoundError, match=r"is a directory, not an image file"):
        load_image(tmp_path)


@pytest.mark.parametrize(
    ("bgr", "hex_colour"), [((0, 0, 255), "#ff0000"), ((200, 120, 30), "#1e78c8"), ((0, 0, 0), "#000000")]
)
def test_an_image_of_one_colour_is_blank_whatever_the_colour(tmp_path, bgr, hex_colour):
    # issue 20, item 18: a red image passed the blank check (its channels differ) and failed later.
    path = tmp_path / "one.png"
    cv2.imwrite(str(path), np.full((64, 80, 3), bgr, np.uint8))
    message = rf"one\.png: image is blank \(one colour, {hex_colour}, in every pixel\); nothing to trace"
    with pytest.raises(InvalidImageError, match=message):
        load_image(path)
    rgb = np.full((64, 80, 3), bgr[::-1], np.uint8)
    with pytest.raises(InvalidImageError, match=r"image is blank \(one colour"):
        load_image(rgb)
    rgb[10, 10] = 255 - rgb[10, 10]  # one pixel of another colour: an image
    assert load_image(rgb).width == 80


# --- third-party lines and EXIF orientation (issue 20, items 6 and 7) ------------------------
def _png_with(tmp_path, name: str, *chunks: tuple[bytes, bytes]):
    """A 64 x 64 px line drawing as a PNG with extra chunks (kind, data) after its IHDR."""

    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    img = np.full((64, 64, 3), 255, np.uint8)
    cv2.circle(img, (32, 32), 20, (0, 0, 0), 3)
    png = cv2.imencode(".png", img)[1].tobytes()
    path = tmp_path / name
    path.write_bytes(png[:33] + b"".join(chunk(k, d) for k, d in chunks) + png[33:])
    return path


@pytest.mark.parametrize(
    "chunks",
    [
        [(b"iCCP", b"bogus\x00\x00" + zlib.compress(b"not a profile" * 10))],
        [
            (b"tEXt", b"Comment\x00" + b"x" * 2_000_000),
            (b"zTXt", b"Comment\x00\x00" + zlib.compress(b"y" * 20_000_000)),
        ],
    ],
    ids=["bogus-iccp", "huge-text"],
)
def test_no_libpng_line_reaches_standard_error(tmp_path, capfd, chunks):
    path = _png_with(tmp_path, "odd.png", *chunks)
    img = load_image(path)
    assert (img.width, img.height) == (64, 64)
    captured = capfd.readouterr()
    assert captured.err == "" and captured.out == ""


def test_other_lines_written_during_a_decode_still_reach_standard_error(tmp_path, capfd, monkeypatch):
    import os

    from img2logo import loading

    decode = cv2.imdecode

    def chatty(*args):
        os.write(2, b"libpng warning: iCCP: known incorrect sRGB profile\nsomeone else's line\n")
        return decode(*args)

    monkeypatch.setattr(cv2, "imdecode", chatty)
    loading.load_image(_png_with(tmp_path, "a.png"))
    assert capfd.readouterr().err == "someone else's line\n"


def test_a_huge_text_chunk_does_not_hide_the_size_from_the_pixel_limit(tmp_path):
    # Pillow refuses the header (MAX_TEXT_CHUNK): the IHDR is read directly, before decoding.
    path = _png_with(tmp_path, "t.png", (b"zTXt", b"Comment\x00\x00" + zlib.compress(b"y" * 20_000_000)))
    with pytest.raises(InvalidImageError, match=r"image is 64x64 px, more than the limit of 1,000 px"):
        load_image(path, max_pixels=1000)


@pytest.mark.parametrize("orientation", range(1, 9))
def test_exif_orientation_is_applied_as_every_viewer_does(tmp_path, orientation):
    from PIL import Image, ImageOps

    # An asymmetric picture: a black bar at the top left, a blue disc lower right.
    arr = np.full((60, 90, 3), 255, np.uint8)
    arr[5:15, 5:40] = 0
    cv2.circle(arr, (65, 40), 12, (30, 60, 220), -1)
    exif = Image.Exif()
    exif[0x0112] = orientation
    path = tmp_path / f"o{orientation}.jpg"
    Image.fromarray(arr).save(path, quality=95, exif=exif.tobytes())
    expected = np.asarray(ImageOps.exif_transpose(Image.open(path)).convert("RGB")) / 255.0
    img = load_image(path)
    assert img.rgb.shape == expected.shape  # 5..8: a quarter turn, 90 x 60 becomes 60 x 90
    assert np.abs(img.rgb - expected).mean() < 0.01  # two JPEG decoders, the same picture


@pytest.mark.parametrize("where", ["before", "after"])
def test_a_png_exif_orientation_is_read_without_decoding_the_pixels(tmp_path, monkeypatch, where):
    """issue 20, item 12: Pillow's PNG getexif() decoded the whole image to look past the pixels (4 s at 144 Mpx)."""
    from PIL import Image, ImageOps, PngImagePlugin

    from img2logo import loading

    arr = np.full((60, 90, 3), 255, np.uint8)
    arr[5:15, 5:40] = 0
    exif = Image.Exif()
    exif[0x0112] = 6
    png = cv2.imencode(".png", arr)[1].tobytes()
    block = exif.tobytes()
    chunk = struct.pack(">I", len(block)) + b"eXIf" + block + struct.pack(">I", zlib.crc32(b"eXIf" + block))
    at = 33 if where == "before" else len(png) - 12  # after the IHDR, or just before the IEND
    path = tmp_path / f"{where}.png"
    path.write_bytes(png[:at] + chunk + png[at:])
    expected = np.asarray(ImageOps.exif_transpose(Image.open(path)).convert("RGB")) / 255.0
    assert expected.shape == (90, 60, 3)

    def no_decode(self):
        raise AssertionError("the header probe decoded the pixels")

    with monkeypatch.context() as m:
        m.setattr(PngImagePlugin.PngImageFile, "load", no_decode)
        assert loading._probe(path, 10**9) == (90, 60, 1, "PNG", 6)
    img = load_image(path)
    assert img.rgb.shape == expected.shape and np.abs(img.rgb - expected).max() < 1e-9


def test_a_phone_photo_stored_sideways_is_upright_when_downscaled(tmp_path):
    from PIL import Image

    arr = np.full((2400, 4400, 3), 255, np.uint8)  # stored landscape, viewed portrait
    arr[100:400, 100:1200] = 0
    exif = Image.Exif()
    exif[0x0112] = 6
    path = tmp_path / "phone.jpg"
    Image.fromarray(arr).save(path, quality=90, exif=exif.tobytes())
    with pytest.warns(DownscaleWarning, match=r"image is 2400x4400 px, .*downscaled to 1117x2048 px"):
        img = load_image(path)
    assert (img.width, img.height) == (1117, 2048)
    assert img.gray[50:150, 1000:1080].mean() < 0.2  # the bar, turned to the top right


def test_a_large_16_bit_rgba_png_is_decoded_once_and_reduced_like_the_area_resize(tmp_path):
    # issue 20, item 12: OpenCV decoded it through a second full-size buffer; Pillow reduces it in 8 bits.
    arr = _shapes(2600, 4300, True).astype(np.uint16) * np.uint16(257)
    path = tmp_path / "big16.png"
    cv2.imwrite(str(path), arr)
    with pytest.warns(DownscaleWarning, match=r"image is 4300x2600 px, .*downscaled to 2048x1238 px"):
        img = load_image(path)
    assert (img.width, img.height, img.has_alpha) == (2048, 1238, True)
    rgb, a = _reference(arr, (2048, 1238))
    assert np.abs(img.rgb - rgb).mean() < 0.005 and np.abs(img.alpha - a).mean() < 0.005
    assert np.percentile(np.abs(img.rgb - rgb), 99) < 0.1  # only edges differ: a box reduce, then the area resize


@pytest.mark.parametrize(("mode", "factor"), [("RGBA", 5), ("RGBA", 2), ("LA", 3), ("RGB", 7), ("L", 1)])
def test_the_strip_by_strip_reduce_gives_pillows_reduce_exactly(mode, factor):
    """issue 20, item 12: Pillow's reduce of RGBA copies the image (premultiplied); strips give the same pixels."""
    from PIL import Image

    from img2logo.loading import _reduce_by_strips

    rng = np.random.default_rng(12)
    channels = {"RGBA": 4, "LA": 2, "RGB": 3, "L": 1}[mode]
    arr = rng.integers(0, 256, (1303, 517, channels), dtype=np.uint8)  # 1303 rows: a partial last strip and block
    im = Image.fromarray(arr[:, :, 0] if channels == 1 else arr, mode)
    assert np.array_equal(_reduce_by_strips(im, factor), np.array(im.reduce(factor)))


def test_a_plain_png_is_probed_without_pillow(tmp_path, monkeypatch):
    # A PNG with neither EXIF nor frames is read without importing Pillow (0.03 s of CPU a run):
    # the same answer as Pillow's probe, and an animation or a cut-short file still goes to Pillow.
    from img2logo import loading

    arr = np.zeros((40, 70, 3), dtype=np.uint8)
    png = cv2.imencode(".png", arr)[1].tobytes()
    plain, cut, animated = tmp_path / "plain.png", tmp_path / "cut.png", tmp_path / "animated.png"
    plain.write_bytes(png)
    cut.write_bytes(png[:-12])
    actl = b"acTL" + struct.pack(">II", 2, 0)
    animated.write_bytes(png[:33] + struct.pack(">I", 8) + actl + struct.pack(">I", zlib.crc32(actl)) + png[33:])
    assert loading._plain_png_size(plain) == (70, 40)
    assert loading._plain_png_size(cut) is None and loading._plain_png_size(animated) is None
    with_pillow = {p: loading._probe(p, 10**9) for p in (plain, cut)}
    monkeypatch.setattr(loading, "_plain_png_size", lambda path: None)
    assert (
        {p: loading._probe(p, 10**9) for p in (plain, cut)}
        == with_pillow
        == {
            plain: (70, 40, 1, "PNG", 1),
            cut: (70, 40, 1, "PNG", 1),
        }
    )
    with pytest.raises(InvalidImageError, match=r"70x40 px, more than the limit"):
        loading._probe(plain, 100)
