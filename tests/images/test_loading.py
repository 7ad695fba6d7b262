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
from img2logo.images import file_checks, reading
from img2logo.images.loading import DownscaleWarning, LoadedImage, PageWarning, composite_on_white, load_image


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


@pytest.mark.parametrize("dtype", [np.uint8, np.uint16, np.float32, np.float64, bool])
@pytest.mark.parametrize("channels", [3, 4])
def test_bgr_is_read_as_the_reversed_colour_channels_to_the_bit(dtype, channels):
    rng = np.random.default_rng(channels)
    if dtype is bool:
        arr = rng.random((9, 7, channels)) > 0.5
    elif np.issubdtype(dtype, np.floating):
        arr = rng.random((9, 7, channels)).astype(dtype)
        arr[0, 0, 0] = -0.0
    else:
        arr = rng.integers(0, np.iinfo(dtype).max + 1, (9, 7, channels)).astype(dtype)
    original = arr.copy()
    for given in (arr, arr[::-1], np.asfortranarray(arr)):  # any memory layout
        want = composite_on_white(np.concatenate([given[:, :, 2::-1], given[:, :, 3:]], axis=2), "x")
        got = composite_on_white(given, "x", bgr=True)
        assert got[0].tobytes() == want[0].tobytes() and got[1].tobytes() == want[1].tobytes()
        assert got[0].flags.c_contiguous and not np.shares_memory(got[0], given)
    assert np.array_equal(arr, original)  # the input is never modified


@pytest.mark.parametrize(
    ("bgr", "hex_colour"), [((0, 0, 255), "#ff0000"), ((200, 120, 30), "#1e78c8"), ((0, 0, 0), "#000000")]
)
def test_an_image_of_one_colour_is_blank_whatever_the_colour(tmp_path, bgr, hex_colour):
    # a red image passed the blank check (its channels differ) and failed later.
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


# --- third-party lines and EXIF orientation ------------------------
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

    from img2logo.images import loading

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
    """Pillow's PNG getexif() decoded the whole image to look past the pixels (4 s at 144 Mpx)."""
    from PIL import Image, ImageOps, PngImagePlugin

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
        assert file_checks.probe(path, 10**9) == (90, 60, 1, "PNG", 6)
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
    # OpenCV decoded it through a second full-size buffer; Pillow reduces it in 8 bits.
    arr = _shapes(2600, 4300, True).astype(np.uint16) * np.uint16(257)
    path = tmp_path / "big16.png"
    cv2.imwrite(str(path), arr)
    with pytest.warns(DownscaleWarning, match=r"image is 4300x2600 px, .*downscaled to 2048x1238 px"):
        img = load_image(path)
    assert (img.width, img.height, img.has_alpha) == (2048, 1238, True)
    rgb, a = _reference(arr, (2048, 1238))
    assert np.abs(img.rgb - rgb).mean() < 0.005 and np.abs(img.alpha - a).mean() < 0.005
    assert np.percentile(np.abs(img.rgb - rgb), 99) < 0.1  # only edges differ: a box reduce, then the area resize


def test_a_plain_png_is_probed_without_pillow(tmp_path, monkeypatch):
    # A PNG with neither EXIF nor frames is read without importing Pillow (0.03 s of CPU a run):
    # the same answer as Pillow's probe, and an animation or a cut-short file still goes to Pillow.

    arr = np.zeros((40, 70, 3), dtype=np.uint8)
    png = cv2.imencode(".png", arr)[1].tobytes()
    plain, cut, animated = tmp_path / "plain.png", tmp_path / "cut.png", tmp_path / "animated.png"
    plain.write_bytes(png)
    cut.write_bytes(png[:-12])
    actl = b"acTL" + struct.pack(">II", 2, 0)
    animated.write_bytes(png[:33] + struct.pack(">I", 8) + actl + struct.pack(">I", zlib.crc32(actl)) + png[33:])
    assert file_checks._plain_png_size(plain) == (70, 40)
    assert file_checks._plain_png_size(cut) is None and file_checks._plain_png_size(animated) is None
    with_pillow = {p: file_checks.probe(p, 10**9) for p in (plain, cut)}
    monkeypatch.setattr(file_checks, "_plain_png_size", lambda path: None)
    assert (
        {p: file_checks.probe(p, 10**9) for p in (plain, cut)}
        == with_pillow
        == {
            plain: (70, 40, 1, "PNG", 1),
            cut: (70, 40, 1, "PNG", 1),
        }
    )
    with pytest.raises(InvalidImageError, match=r"70x40 px, more than the limit"):
        file_checks.probe(plain, 100)


# --------------------------------------------------------------------------- a large PNG, strip by strip
def _refused_in_one_line(path, match: str, max_side: int) -> None:
    """``load_image`` refuses ``path`` with a one-line message matching ``match``, whatever it would downscale."""
    with pytest.raises(InvalidImageError, match=match) as caught:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", DownscaleWarning)
            load_image(path, max_side=max_side)
    assert "\n" not in str(caught.value)


def _box_mean(arr: np.ndarray, factor: int, alpha: bool) -> np.ndarray:
    """Reference of the large-image reduce: (H, W, C) samples to the float box means (colour premultiplied),
    the last boxes filled out with the edge pixels."""
    a = arr.astype(np.float64)
    h, w, c = a.shape
    big_h, big_w = -(-h // factor), -(-w // factor)
    pad = np.pad(a, ((0, big_h * factor - h), (0, big_w * factor - w), (0, 0)), mode="edge")
    boxes = pad.reshape(big_h, factor, big_w, factor, c)
    if not alpha:
        return boxes.mean(axis=(1, 3))
    op = boxes[..., -1:]
    sum_a = op.sum(axis=(1, 3))
    colour = (boxes[..., :-1] * op).sum(axis=(1, 3)) / np.where(sum_a > 0, sum_a, 1.0)
    return np.concatenate([np.where(sum_a > 0, colour, 0.0), sum_a / factor**2], axis=2)


def _noisy(h: int, w: int, channels: int, dtype: type, seed: int = 3) -> np.ndarray:
    """A smooth picture with noise: (H, W, C) of ``dtype``, every filter type worth choosing."""
    rng = np.random.default_rng(seed)
    coarse = rng.uniform(0, 255, (h // 16 + 2, w // 16 + 2, channels)).astype(np.float32)
    smooth = cv2.resize(coarse, (w, h), interpolation=cv2.INTER_CUBIC).reshape(h, w, channels)
    values = np.clip(smooth + rng.normal(0, 6, smooth.shape), 0, 255)
    return (values * 257).astype(np.uint16) if dtype == np.uint16 else values.astype(np.uint8)


@pytest.mark.parametrize(
    ("channels", "dtype", "factor", "png_filter"),
    [
        (4, np.uint16, 5, "FILTER_PAETH"),
        (4, np.uint8, 3, "ALL_FILTERS"),
        (3, np.uint16, 2, "FILTER_AVG"),
        (3, np.uint8, 7, "FILTER_UP"),
        (1, np.uint16, 4, "FILTER_SUB"),
        (1, np.uint8, 1, "ALL_FILTERS"),
    ],
)
def test_a_large_png_read_through_libvips_is_its_box_reduce(tmp_path, channels, dtype, factor, png_filter):
    # The full-size image is never in memory; the result is the box mean to rounding, at the file's depth,
    # whatever the row filters.

    arr = _noisy(301, 517, channels, dtype)
    path = tmp_path / "big.png"
    filters = (
        [cv2.IMWRITE_PNG_FILTER, getattr(cv2, f"IMWRITE_PNG_{png_filter}")]
        if hasattr(cv2, "IMWRITE_PNG_FILTER")
        else []
    )
    cv2.imwrite(str(path), arr[:, :, 0] if channels == 1 else arr, filters)
    got = reading._read_with_vips(path, "PNG", factor)
    assert got.dtype == dtype
    expected = _box_mean(arr, factor, channels == 4)
    assert got.reshape(expected.shape).shape == expected.shape
    assert np.abs(got.reshape(expected.shape) - expected).max() <= 0.5  # rounded to the file's depth


def test_a_large_palette_low_depth_or_colour_key_png_is_its_box_reduce(tmp_path):
    from PIL import Image

    arr = _noisy(207, 333, 3, np.uint8)
    arr[50:80, 20:90] = (10, 20, 30)
    cases = {
        "p.png": (Image.fromarray(arr).quantize(64), {}),
        "pa.png": (Image.fromarray(arr).quantize(64), {"transparency": bytes(range(0, 256, 4))}),
        "one.png": (Image.fromarray(arr[:, :, 0] > 128), {}),
        "four.png": (Image.fromarray(arr[:, :, 0]), {"bits": 4}),
        "key.png": (Image.fromarray(arr), {"transparency": (10, 20, 30)}),
    }
    for name, (im, options) in cases.items():
        path = tmp_path / name
        im.save(path, **options)
        got = reading._read_with_vips(path, "PNG", 3)
        rgba = np.array(Image.open(path).convert("RGBA"))[:, :, [2, 1, 0, 3]]
        expected = _box_mean(rgba, 3, True)
        if got.ndim == 2:
            got = np.dstack([got] * 3)
        if got.shape[2] == 3:
            got = np.dstack([got, np.full(got.shape[:2], 255)])
        visible = expected[:, :, 3] > 0
        assert np.abs(got[:, :, 3] - expected[:, :, 3]).max() <= 0.5, name
        assert np.abs(got[visible][:, :3] - expected[visible][:, :3]).max() <= 0.5, name


def test_a_large_png_stored_sideways_is_upright_through_libvips(tmp_path, monkeypatch):
    from PIL import Image

    calls = []
    vips = reading._read_with_vips
    monkeypatch.setattr(
        reading, "_read_with_vips", lambda path, fmt, factor: calls.append(factor) or vips(path, fmt, factor)
    )
    arr = np.full((240, 440, 3), 255, np.uint8)  # stored landscape, viewed portrait
    arr[10:40, 10:120] = 0
    exif = Image.Exif()
    exif[0x0112] = 6
    path = tmp_path / "phone.png"
    Image.fromarray(arr).save(path, exif=exif.tobytes())
    with pytest.warns(DownscaleWarning, match=r"image is 240x440 px, .*downscaled to 35x64 px"):
        img = load_image(path, max_side=64)
    assert calls == [6] and (img.width, img.height, img.input_size) == (35, 64, (240, 440))
    assert img.gray[1:6, 30:34].mean() < 0.3 and img.gray[58:63, 1:5].mean() > 0.9  # the bar, at the top right


@pytest.mark.parametrize(
    ("damage", "message"),
    [
        ("cut", r"not a readable image: the PNG ends before its IEND chunk \(the file cut short\?\)"),
        ("flip", r"not a readable image"),
        ("no IEND", r"not a readable image: the PNG ends before its IEND chunk \(the file cut short\?\)"),
    ],
)
@pytest.mark.parametrize("max_side", [64, 2048])
def test_a_cut_or_damaged_png_is_one_line_at_any_size(tmp_path, damage, message, max_side):
    # One rule for a damaged PNG whether it is downscaled (libvips) or not (OpenCV): a PNG missing only
    # its IEND chunk was refused at 512 px and read at 4000 px.
    arr = _noisy(300, 410, 4, np.uint16)
    data = bytearray(cv2.imencode(".png", arr)[1].tobytes())
    if damage == "cut":
        data = data[: len(data) // 2]
    elif damage == "no IEND":
        data = data[:-12]
    else:
        middle = len(data) // 2
        data[middle : middle + 64] = bytes(64)
    path = tmp_path / "big.png"
    path.write_bytes(bytes(data))
    _refused_in_one_line(path, r"big\.png: " + message, max_side)
    trailing = tmp_path / "trailing.png"  # bytes after IEND are not damage: libpng ignores them
    trailing.write_bytes(cv2.imencode(".png", arr)[1].tobytes() + bytes(70000))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DownscaleWarning)
        assert load_image(trailing, max_side=max_side).input_size == (410, 300)


def test_a_large_interlaced_png_is_its_box_reduce(tmp_path):
    import pyvips
    from PIL import Image

    arr = _noisy(40, 50, 3, np.uint8)
    path = tmp_path / "adam7.png"
    pyvips.Image.new_from_array(arr).copy(interpretation="srgb").pngsave(str(path), interlace=True)
    assert Image.open(path).info.get("interlace") == 1
    got = reading._read_with_vips(path, "PNG", 2)
    assert np.abs(got.astype(float) - _box_mean(arr[:, :, ::-1], 2, False)).max() <= 0.5


def test_a_large_png_is_probed_up_to_its_pixels_and_its_exif_after_them_still_turns_it(tmp_path, monkeypatch):
    # the probe walked a huge PNG's 100 000 IDAT chunks (1.5 s) before the strip
    # decoder walked them again; it stops at the first IDAT, and the strip decoder reads an eXIf after them.
    from PIL import Image, ImageOps

    arr = _noisy(240, 440, 3, np.uint8)
    exif = Image.Exif()
    exif[0x0112] = 6
    block = exif.tobytes()
    chunk = struct.pack(">I", len(block)) + b"eXIf" + block + struct.pack(">I", zlib.crc32(b"eXIf" + block))
    png = cv2.imencode(".png", arr)[1].tobytes()
    path, before = tmp_path / "after.png", tmp_path / "before.png"
    path.write_bytes(png[:-12] + chunk + png[-12:])
    before.write_bytes(png[:33] + chunk + png[33:])  # the probe reads it (Pillow), the strip decoder decodes it
    walked = []
    seek = file_checks._plain_png_size
    monkeypatch.setattr(
        file_checks, "_plain_png_size", lambda p, **kw: walked.append(kw.get("pixels_first", False)) or seek(p, **kw)
    )
    assert file_checks.probe(path, 10**9, max_side=64) == (440, 240, 1, "PNG", 1)
    assert walked == [True]  # no second walk over the pixel data's chunks
    with pytest.warns(DownscaleWarning, match=r"image is 240x440 px"):
        img = load_image(path, max_side=64)
    with pytest.warns(DownscaleWarning, match=r"image is 240x440 px"):
        ref = load_image(before, max_side=64)
    assert (img.input_size, img.rgb.shape[:2]) == ((240, 440), (64, 35))
    assert np.array_equal(img.rgb, ref.rgb)  # turned as every viewer shows it
    upright = np.asarray(ImageOps.exif_transpose(Image.open(path)))
    small = cv2.resize(upright, (35, 64), interpolation=cv2.INTER_AREA) / 255.0
    assert np.abs(img.rgb - small).mean() < 0.1  # not the other way round (a quarter turn: 0.2)


# --------------------------------------------------------------------------- a large TIFF, band by band
def _tiff_reference(path) -> np.ndarray:
    """The whole image decoded as (H, W, C), grey or BGR(A): tifffile's decode (an oracle: OpenCV 5.1 decodes
    16-bit separate planes wrongly), OpenCV's channel order."""
    import tifffile

    with tifffile.TiffFile(path) as tif:
        page = tif.pages[0]
        arr = page.asarray()
        if page.planarconfig == 2:
            arr = np.moveaxis(arr, 0, 2)
    if arr.ndim == 2:
        return arr[:, :, None]
    return arr[:, :, [2, 1, 0, *range(3, arr.shape[2])]]


def _cv_tiff(path, arr: np.ndarray, compression: int, rows: int, predictor: bool) -> None:
    params = [cv2.IMWRITE_TIFF_COMPRESSION, compression, cv2.IMWRITE_TIFF_ROWSPERSTRIP, rows]
    if predictor:
        params += [cv2.IMWRITE_TIFF_PREDICTOR, 2]
    assert cv2.imwrite(str(path), arr[:, :, 0] if arr.shape[2] == 1 else arr, params)


@pytest.mark.parametrize(
    ("channels", "dtype", "compression", "rows", "predictor", "factor"),
    [
        (4, np.uint16, 5, 1, True, 5),  # OpenCV's own TIFF: LZW, the horizontal predictor, a strip a row
        (4, np.uint8, 5, 7, False, 3),
        (3, np.uint16, 8, 16, True, 4),  # deflate
        (3, np.uint8, 32773, 5, False, 2),  # PackBits
        (1, np.uint16, 1, 300, False, 3),  # uncompressed, one strip: split into strips of a band's bytes
        (1, np.uint8, 32946, 3, True, 1),  # deflate, the old code
        (4, np.uint16, 1, 9, False, 7),
    ],
)
def test_a_large_tiff_read_through_libvips_is_its_box_reduce(
    tmp_path, channels, dtype, compression, rows, predictor, factor
):
    # The whole image is never in memory; the result is the box mean of the whole image to rounding, at
    # the file's depth (tifffile's decode, the oracle).

    arr = _noisy(301, 517, channels, dtype)
    path = tmp_path / "big.tif"
    _cv_tiff(path, arr, compression, rows, predictor)
    got = reading._read_with_vips(path, "TIFF", factor)
    assert got.dtype == dtype
    whole = arr  # what was written, without loss
    expected = _box_mean(whole, factor, channels == 4)
    assert np.abs(got.reshape(expected.shape) - expected).max() <= 0.5  # rounded to the file's depth


@pytest.mark.parametrize(
    ("channels", "dtype", "layout", "factor"),
    [
        (4, np.uint16, {"tile": (64, 48), "compression": "zlib", "predictor": True}, 5),
        (3, np.uint8, {"tile": (32, 80)}, 3),
        (4, np.uint16, {"planarconfig": "separate", "rowsperstrip": 6, "compression": "zlib"}, 4),
        (3, np.uint8, {"planarconfig": "separate", "rowsperstrip": 5}, 2),
        (4, np.uint16, {"byteorder": ">", "rowsperstrip": 4, "compression": "zlib", "predictor": True}, 3),
        (1, np.uint16, {"byteorder": ">", "bigtiff": True, "rowsperstrip": 8}, 2),
    ],
)
def test_a_large_tiled_planar_or_big_endian_tiff_is_its_box_reduce(tmp_path, channels, dtype, layout, factor):
    import tifffile

    arr = _noisy(301, 517, channels, dtype)
    rgb = arr[:, :, 0] if channels == 1 else arr  # RGB(A) as tifffile writes it
    if layout.get("planarconfig") == "separate":
        rgb = np.ascontiguousarray(np.moveaxis(rgb, 2, 0))
    path = tmp_path / "big.tif"
    extra = {"extrasamples": ["unassalpha"]} if channels == 4 else {}
    tifffile.imwrite(path, rgb, photometric="minisblack" if channels == 1 else "rgb", **extra, **layout)
    got = reading._read_with_vips(path, "TIFF", factor)
    assert got.dtype == dtype
    reference = _tiff_reference(path)
    assert np.array_equal(
        reference[:, :, :3] if channels >= 3 else reference, arr[:, :, :3][:, :, ::-1] if channels >= 3 else arr
    )
    expected = _box_mean(reference, factor, channels == 4)
    assert np.abs(got.reshape(expected.shape) - expected).max() <= 0.5


def test_a_tiff_of_tiles_in_separate_planes_is_refused_in_one_line(tmp_path):
    # libvips does not read this layout (OpenCV decoded its 16-bit samples wrongly): said, not misread.
    import tifffile

    path = tmp_path / "big.tif"
    planes = np.ascontiguousarray(np.moveaxis(_noisy(301, 517, 3, np.uint16), 2, 0))
    tifffile.imwrite(path, planes, photometric="rgb", tile=(32, 32), planarconfig="separate")
    # libvips's closing "load error" lands before or after the reason as its threads finish: the reason every time
    for _ in range(20):
        with pytest.raises(
            InvalidImageError, match=r"big\.tif: not a readable image: tiff2vips: tiled separate planes not supported$"
        ):
            load_image(path)


@pytest.mark.parametrize("compression", ["tiff_lzw", "packbits", "raw"])
def test_a_large_palette_or_grey_tiff_is_pillows_decode_box_reduced(tmp_path, compression):
    from PIL import Image

    rgb = Image.fromarray(_noisy(301, 517, 3, np.uint8)[:, :, ::-1])
    for mode in ("P", "L"):
        im = rgb.quantize(64) if mode == "P" else rgb.convert("L")
        path = tmp_path / f"{mode}.tif"
        im.save(path, compression=compression)
        got = reading._read_with_vips(path, "TIFF", 3)
        full = np.asarray(im.convert("RGB"))[:, :, ::-1] if mode == "P" else np.asarray(im)[:, :, None]
        expected = _box_mean(full, 3, False)
        assert np.abs(got.reshape(expected.shape) - expected).max() <= 0.5


@pytest.mark.parametrize("damage", ["cut", "stream", "offsets"])
@pytest.mark.parametrize("max_side", [64, 2048])
def test_a_cut_or_damaged_tiff_is_one_line_at_any_size(tmp_path, damage, max_side):
    path = tmp_path / "big.tif"
    _cv_tiff(path, _noisy(300, 410, 4, np.uint16), 8, 4, True)
    data = bytearray(path.read_bytes())
    if damage == "cut":
        data = data[: len(data) // 2]
    elif damage == "stream":  # every strip's deflate header, or its checksum, broken
        data[len(data) // 3 : len(data) * 2 // 3 : 97] = bytes(len(data[len(data) // 3 : len(data) * 2 // 3 : 97]))
    else:  # the strips point past the end of the file: StripOffsets (273) rewritten
        import tifffile

        with tifffile.TiffFile(path) as tif:
            tag = tif.pages[0].tags[273]
            offsets, at, kind = tag.value, tag.valueoffset, tag.dtype
        fmt = {3: "H", 4: "I", 16: "Q"}[int(kind)]
        struct.pack_into(f"<{len(offsets)}{fmt}", data, at, *[o + len(data) for o in offsets])
    path.write_bytes(bytes(data))
    _refused_in_one_line(path, r"big\.tif: not a readable image", max_side)


def test_a_tiff_in_strips_over_the_byte_budget_is_refused(tmp_path, monkeypatch):
    # libtiff decodes a strip whole: one strip of the whole image is the whole image in memory.
    import tifffile

    path = tmp_path / "one-strip.tif"  # 16-bit RGBA in one deflated strip: 8 bytes a pixel
    tifffile.imwrite(path, _noisy(50, 70, 4, np.uint16), photometric="rgb", compression="zlib", extrasamples=[2])
    monkeypatch.setattr(file_checks, "MAX_WHOLE_TIFF_BYTES", 50 * 70 * 8 - 1)
    message = (
        r"one-strip\.tif: image is a TIFF in strips of 0 MB of samples each, and a strip or tile is decoded whole; "
        r"img2logo reads such a file up to 0 MB a strip \(its memory limit\): downscale it, or save it in smaller "
        r"strips or tiles"
    )
    with pytest.raises(InvalidImageError, match=message):
        load_image(path)
    monkeypatch.setattr(file_checks, "MAX_WHOLE_TIFF_BYTES", 50 * 70 * 8)
    assert load_image(path).input_size == (70, 50)
    tiled = tmp_path / "tiled.tif"
    tifffile.imwrite(tiled, _noisy(50, 70, 3, np.uint8), photometric="rgb", tile=(32, 32))
    monkeypatch.setattr(file_checks, "MAX_WHOLE_TIFF_BYTES", 32 * 32 * 3 - 1)
    with pytest.raises(InvalidImageError, match=r"tiled\.tif: image is a TIFF in tiles of"):
        load_image(tiled)


def test_a_large_jpeg_2000_is_decoded_at_a_reduced_resolution(tmp_path):
    # OpenJPEG decoded a 12000 px file whole (2.3 GB); Pillow stops wavelet levels short.
    from PIL import Image

    arr = _shapes(1000, 1400, False)
    path = tmp_path / "big.jp2"
    Image.fromarray(arr[:, :, ::-1]).save(path)
    with pytest.warns(DownscaleWarning, match=r"big\.jp2: image is 1400x1000 px, .*downscaled to 300x214 px"):
        img = load_image(path, max_side=300)
    with Image.open(path) as im:
        im.reduce = 2  # 1400 / 4 = 350 >= 300 > 1400 / 8
        im.load()
        quarter = np.asarray(im)
    assert quarter.shape == (250, 350, 3)
    rgb, _ = _reference(quarter[:, :, ::-1], (300, 214))
    assert np.abs(img.rgb - rgb).max() < 1.5 / 255
    damaged = tmp_path / "cut.jp2"
    damaged.write_bytes(path.read_bytes()[: path.stat().st_size // 3])
    _refused_in_one_line(damaged, r"cut\.jp2: not a readable image", 300)


@pytest.mark.parametrize("suffix", [".hdr", ".pfm"])
def test_a_floating_point_image_over_its_limit_is_refused_before_decoding(tmp_path, monkeypatch, suffix):

    path = tmp_path / f"big{suffix}"
    assert cv2.imwrite(str(path), np.full((30, 50, 3), 0.5, np.float32))
    assert reading._float_image_size(path)[:2] == (50, 30)
    monkeypatch.setattr(reading, "MAX_FLOAT_IMAGE_PIXELS", 1000)
    decoded = []
    monkeypatch.setattr(cv2, "imdecode", lambda *a: decoded.append(a) or None)
    kind = "Radiance HDR" if suffix == ".hdr" else "PFM"
    with pytest.raises(
        InvalidImageError, match=rf"image is 50x30 px of floating-point samples \({kind}\); .* 1,000 px"
    ):
        load_image(path)
    assert decoded == []


def test_a_large_file_is_decoded_from_the_file_with_the_same_bits(tmp_path, monkeypatch):
    # From STREAM_DECODE_BYTES (64 MB) on OpenCV reads the file itself rather than a copy of its bytes.

    arr = _shapes(300, 400, True)
    path = tmp_path / "big.bmp"
    assert cv2.imwrite(str(path), arr)
    small = load_image(path)
    monkeypatch.setattr(reading, "STREAM_DECODE_BYTES", 1000)
    read = []
    imread = cv2.imread
    monkeypatch.setattr(cv2, "imread", lambda *a: read.append(a) or imread(*a))
    streamed = load_image(path)
    assert len(read) == 1 and np.array_equal(streamed.rgb, small.rgb) and np.array_equal(streamed.alpha, small.alpha)


@pytest.mark.parametrize("transparent", [False, True])
def test_a_large_gif_is_decoded_as_its_palette_and_reduced_by_strips(tmp_path, transparent):
    # OpenCV decoded a 12000 px GIF through full-size BGRA canvases (1.8 GB).
    from PIL import Image

    im = Image.fromarray(_shapes(600, 700, False)[:, :, ::-1]).quantize(16)
    path = tmp_path / "big.gif"
    im.save(path, **({"transparency": 0} if transparent else {}))
    with pytest.warns(DownscaleWarning, match=r"big\.gif: image is 700x600 px"):
        img = load_image(path, max_side=200)
    with Image.open(path) as again:
        full = np.asarray(again.convert("RGBA" if transparent else "RGB"))[
            :, :, [2, 1, 0, *([3] if transparent else [])]
        ]
    rgb, a = _reference(np.ascontiguousarray(full), (img.width, img.height))
    assert img.has_alpha is transparent
    assert np.abs(img.rgb - rgb).mean() < 0.01 and np.abs(img.alpha - a).mean() < 0.01  # reduce by 3, then area
    cut = tmp_path / "cut.gif"
    cut.write_bytes(path.read_bytes()[:200])
    _refused_in_one_line(cut, r"cut\.gif: not a readable image", 200)


@pytest.mark.parametrize(("channels", "dtype", "factor"), [(3, np.uint16, 3), (1, np.uint8, 4), (3, np.uint8, 2)])
def test_a_large_ppm_is_read_by_libvips_as_its_box_reduce(tmp_path, channels, dtype, factor):
    # OpenCV decoded a 12000 px 16-bit PPM through a second full-size buffer (1.75 GB).

    arr = _noisy(301, 517, channels, dtype)
    path = tmp_path / ("big.ppm" if channels == 3 else "big.pgm")
    assert cv2.imwrite(str(path), arr if channels == 3 else arr[:, :, 0])
    got = reading._read_netpbm_reduced(path, factor)
    assert got is not None and got.dtype == dtype
    whole = cv2.imread(str(path), cv2.IMREAD_UNCHANGED)
    expected = _box_mean(whole if whole.ndim == 3 else whole[:, :, None], factor, False)
    assert np.abs(got.reshape(expected.shape) - expected).max() <= 0.5
    cut = tmp_path / "cut.ppm"
    cut.write_bytes(path.read_bytes()[: path.stat().st_size // 2])
    _refused_in_one_line(cut, r"cut\.ppm: not a readable image: its pixel data ends", 64)


# --------------------------------------------------------------------------- hostile and unusual files
def _classic_tiff(entries: list[tuple[int, int, int]], pixels: bytes) -> bytes:
    """A little-endian TIFF of one IFD: ``entries`` (tag, type, value) in the given order (SHORT 3 or LONG 4,
    one value each), StripOffsets pointing at ``pixels`` after the IFD."""
    at = 8 + 2 + 12 * (len(entries) + 1) + 4
    ifd = struct.pack("<H", len(entries) + 1)
    for tag, kind, value in [*entries, (273, 4, at)]:
        ifd += struct.pack("<HHI", tag, kind, 1) + struct.pack("<H2x" if kind == 3 else "<I", value)
    return b"II*\x00" + struct.pack("<I", 8) + ifd + struct.pack("<I", 0) + pixels


def test_a_large_tiff_with_a_second_compression_tag_of_another_type_is_read_or_one_line(tmp_path):
    # The hand-written band parser raised KeyError: 2 for such a file over 2048 px; libvips reads it.
    width, height = 2100, 16
    pixels = np.zeros((height, width), np.uint8)
    pixels[4:12, 100:2000] = 255
    entries = [(256, 3, width), (257, 3, height), (258, 3, 8), (259, 3, 1), (259, 4, 2), (262, 3, 1)]
    entries += [(277, 3, 1), (278, 3, height), (279, 4, width * height)]
    path = tmp_path / "two-compressions.tif"
    path.write_bytes(_classic_tiff(entries, pixels.tobytes()))
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", DownscaleWarning)
            img = load_image(path)
    except InvalidImageError as exc:
        assert "not a readable image" in str(exc) and "\n" not in str(exc)
    else:
        assert img.input_size == (width, height) and img.gray.min() < 0.1 < 0.9 < img.gray.max()


@pytest.mark.parametrize("tag", [256, 257, 258, 273, 277, 278, 279, 322, 323, 324, 325, 338])
def test_an_88_byte_bigtiff_of_hostile_counts_is_not_a_readable_image(tmp_path, tag):
    # A BigTIFF header and three 20-byte entries, the last one's count 2**40: no "out of memory", one line.
    data = b"II" + struct.pack("<HHHQ", 43, 8, 0, 16) + struct.pack("<Q", 3)
    for t, kind, count, value in [(256, 4, 1, 2**31), (257, 4, 1, 3000), (tag, 16, 2**40, 16)]:
        data += struct.pack("<HHQQ", t, kind, count, value)
    data += bytes(4)
    assert len(data) == 88
    path = tmp_path / "bigtiff.tif"
    path.write_bytes(data)
    with pytest.raises(
        InvalidImageError, match=r"bigtiff\.tif: (not a readable image|image is .* more than)"
    ) as caught:
        load_image(path)
    assert "\n" not in str(caught.value)


@pytest.mark.parametrize("depth", [8, 16])
def test_an_rgba_tiff_has_its_alpha_applied_once(tmp_path, depth):
    # OpenCV's libtiff read of an 8-bit RGBA TIFF premultiplied the colour: a 50 % grey of 200 came out 177.
    import tifffile

    full = 255 if depth == 8 else 65535
    arr = np.zeros((32, 40, 4), np.uint8 if depth == 8 else np.uint16)
    arr[..., :3] = 200 * full // 255
    arr[..., 3] = full // 2 + 1
    arr[:8, :8] = (0, 0, 0, full)  # not blank
    path = tmp_path / "grey.tif"
    tifffile.imwrite(path, arr, photometric="rgb", extrasamples=["unassalpha"])
    img = load_image(path)
    expected = 200 / 255 * img.alpha[20, 20] + (1 - img.alpha[20, 20])
    assert img.has_alpha and img.alpha[20, 20] == pytest.approx(0.5, abs=0.01)
    assert img.rgb[20, 20] * 255 == pytest.approx([expected * 255] * 3, abs=0.5)  # 227.5, not 177


def _progressive_jpeg(repeat: int) -> bytes:
    """A progressive JPEG (Pillow's) whose last scan is repeated ``repeat`` more times before EOI."""
    import io

    from PIL import Image

    buf = io.BytesIO()
    Image.fromarray(_noisy(96, 128, 3, np.uint8)).save(buf, "JPEG", quality=90, progressive=True)
    data = buf.getvalue()
    last = data.rindex(b"\xff\xda")
    return data[:-2] + data[last:-2] * repeat + data[-2:]


def test_a_progressive_jpeg_with_a_repeated_scan_is_refused_before_decoding(tmp_path, monkeypatch):
    # A 113 KB file of repeated scans decoded for 31 s (each scan is a pass over every block).
    path = tmp_path / "repeated.jpg"
    path.write_bytes(_progressive_jpeg(40))
    decoded = []
    monkeypatch.setattr(cv2, "imdecode", lambda *a: decoded.append(a) or None)
    message = r"repeated\.jpg: not a readable image: scan \d+ of the JPEG codes again what an earlier scan coded"
    with pytest.raises(InvalidImageError, match=message) as caught:
        load_image(path)
    assert "\n" not in str(caught.value) and decoded == []
    monkeypatch.undo()
    good = tmp_path / "good.jpg"
    good.write_bytes(_progressive_jpeg(0))
    assert load_image(good).input_size == (128, 96)


def test_a_jpeg_of_too_many_scans_is_refused(tmp_path, monkeypatch):

    path = tmp_path / "scans.jpg"
    path.write_bytes(_progressive_jpeg(0))
    scans = path.read_bytes().count(b"\xff\xda")
    monkeypatch.setattr(file_checks, "MAX_JPEG_SCANS", scans - 1)
    with pytest.raises(
        InvalidImageError, match=rf"scans\.jpg: not a readable image: the JPEG has more than {scans - 1}"
    ):
        load_image(path)


@pytest.mark.parametrize("frames", ["none", "zero-size", "wider than the image"])
def test_a_malformed_animated_png_is_read_as_its_default_image_not_all_black(tmp_path, frames):
    # An acTL chunk promising frames whose fcTL is missing or malformed: OpenCV gave all black ("blank").
    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    arr = np.full((40, 50, 3), 255, np.uint8)
    arr[10:30, 10:40] = (0, 0, 200)
    png = cv2.imencode(".png", arr)[1].tobytes()
    width = {"none": 0, "zero-size": 0, "wider than the image": 500}[frames]
    fctl = (
        b""
        if frames == "none"
        else chunk(b"fcTL", struct.pack(">IIIIIHHBB", 0, width, width and 40, 0, 0, 1, 10, 0, 0))
    )
    path = tmp_path / "animated.png"
    path.write_bytes(png[:33] + chunk(b"acTL", struct.pack(">II", 2, 0)) + fctl + png[33:])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PageWarning)
        img = load_image(path)
    assert np.abs(img.rgb - composite_on_white(arr, bgr=True)[0]).max() < 1e-9  # the IDAT's picture


def test_no_libjpeg_warning_reaches_standard_error(tmp_path, capfd):
    # A sequential JPEG whose scan header names a spectral band (Se = 62): libjpeg decodes it and prints
    # "Invalid SOS parameters for sequential JPEG" to standard error itself, which -q must not show.
    import io

    from PIL import Image

    buf = io.BytesIO()
    Image.fromarray(_noisy(64, 80, 3, np.uint8)).save(buf, "JPEG", quality=90)
    data = bytearray(buf.getvalue())
    sos = data.index(b"\xff\xda")
    n = data[sos + 4]
    assert data[sos + 5 + 2 * n + 1] == 63  # Se
    data[sos + 5 + 2 * n + 1] = 62
    path = tmp_path / "sos.jpg"
    path.write_bytes(bytes(data))
    img = load_image(path)
    assert (img.width, img.height) == (80, 64)
    captured = capfd.readouterr()
    assert captured.err == "" and captured.out == ""


@pytest.mark.parametrize(("mode", "factor"), [("RGBA", 5), ("RGBA", 2), ("LA", 3), ("RGB", 7), ("L", 1)])
def test_the_strip_by_strip_reduce_gives_pillows_reduce_exactly(mode, factor):
    """Pillow's reduce of RGBA copies the image (premultiplied); strips give the same pixels."""
    from PIL import Image

    from img2logo.images.reading import reduce_by_strips

    rng = np.random.default_rng(12)
    channels = {"RGBA": 4, "LA": 2, "RGB": 3, "L": 1}[mode]
    arr = rng.integers(0, 256, (1303, 517, channels), dtype=np.uint8)  # 1303 rows: a partial last strip and block
    im = Image.fromarray(arr[:, :, 0] if channels == 1 else arr, mode)
    assert np.array_equal(reduce_by_strips(im, factor), np.array(im.reduce(factor)))


def test_flat_fraction_counts_pixels_whose_four_neighbours_have_their_8_bit_colour():
    rng = np.random.default_rng(11)
    for _ in range(60):
        h, w = (int(v) for v in rng.integers(1, 30, 2))
        levels = int(rng.choice([2, 4, 256]))  # few colours (many flat pixels) to every 8-bit one
        rgb = np.round(rng.random((h, w, 3)) * (levels - 1)) / (levels - 1)
        if rng.random() < 0.3:  # values between the 8-bit ones: rounded to them
            rgb = np.clip(rgb + rng.normal(0.0, 0.002, rgb.shape), 0.0, 1.0)
        codes = np.round(rgb * 255.0).astype(np.int64) @ np.array([1 << 16, 1 << 8, 1])
        padded = np.pad(codes, 1, mode="edge")  # the frame's missing neighbours count as equal
        same = (
            (padded[1:-1, :-2] == codes)
            & (padded[1:-1, 2:] == codes)
            & (padded[:-2, 1:-1] == codes)
            & (padded[2:, 1:-1] == codes)
        )
        assert LoadedImage(rgb, np.ones((h, w))).flat_fraction == float(same.mean())
