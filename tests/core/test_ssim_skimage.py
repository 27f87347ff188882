"""Facet's image metrics against scikit-image's on real image pairs.

SSIM: skimage.metrics.structural_similarity(gaussian_weights=True, sigma=1.5,
use_sample_covariance=False, data_range=255) — Wang et al. 2004's settings — on the BT.709
luminance Facet uses (computed here exactly as the core does: 8-bit values divided by 255 in
float32, then weighted in double and scaled by 255). RMSE and PSNR: mean_squared_error and
peak_signal_noise_ratio on the RGB arrays. The pairs: photographs shipped with scikit-image
under noise, blur, JPEG compression, a shift and a brightness change, and a Facet flat render
against its analytic reference.

Usage: test_ssim_skimage.py FACET_IMAGE_METRICS_TOOL
"""

import io
import json
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np
from PIL import Image
from scipy import ndimage
from skimage import data
from skimage.metrics import mean_squared_error, peak_signal_noise_ratio, structural_similarity

TOOL = sys.argv.pop(1) if len(sys.argv) > 1 else os.environ.get("FACET_IMAGE_METRICS_TOOL")
# Same inputs, same formula; only the order of the filter's sums differs (~1e-16 each).
SSIM_TOLERANCE = 1e-9
WEIGHTS = (0.2126, 0.7152, 0.0722)


def luminance(rgb):
    channels = [(rgb[..., i].astype(np.float32) / np.float32(255)).astype(np.float64) for i in range(3)]
    return 255.0 * (WEIGHTS[0] * channels[0] + WEIGHTS[1] * channels[1] + WEIGHTS[2] * channels[2])


def skimage_ssim(a, b):
    return structural_similarity(luminance(a), luminance(b), gaussian_weights=True, sigma=1.5,
                                 use_sample_covariance=False, data_range=255)


def rgb(image):
    return np.stack([image] * 3, axis=-1) if image.ndim == 2 else image[..., :3]


def degraded_pairs():
    rng = np.random.default_rng(20261121)
    photos = {"camera": rgb(data.camera()), "astronaut": rgb(data.astronaut()),
              "chelsea": rgb(data.chelsea())}
    for name, photo in photos.items():
        noisy = np.clip(photo + rng.normal(0.0, 12.0, photo.shape), 0, 255).astype(np.uint8)
        blurred = ndimage.gaussian_filter(photo.astype(np.float64), sigma=(2.0, 2.0, 0.0))
        jpeg = io.BytesIO()
        Image.fromarray(photo).save(jpeg, format="JPEG", quality=20)
        brighter = np.clip(photo.astype(np.int32) + 25, 0, 255).astype(np.uint8)
        yield name + " noise", photo, noisy
        yield name + " blur", photo, np.clip(blurred + 0.5, 0, 255).astype(np.uint8)
        yield name + " jpeg", photo, np.asarray(Image.open(jpeg).convert("RGB"))
        yield name + " shift", photo, np.roll(photo, (3, -2), axis=(0, 1))
        yield name + " brighter", photo, brighter


class SsimAgainstSkimage(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.TemporaryDirectory()

    def tearDown(self):
        self.folder.cleanup()

    def path(self, name):
        return os.path.join(self.folder.name, name)

    def facet_metrics(self, a_path, b_path):
        out = subprocess.run([TOOL, "compare", a_path, b_path], check=True, capture_output=True,
                             text=True).stdout
        return json.loads(out)

    def check_pair(self, label, a, b):
        Image.fromarray(a).save(self.path("a.png"))
        Image.fromarray(b).save(self.path("b.png"))
        ours = self.facet_metrics(self.path("a.png"), self.path("b.png"))
        theirs = skimage_ssim(a, b)
        print(f"{label:22s} SSIM facet {ours['ssim']:.15f} skimage {theirs:.15f} "
              f"diff {abs(ours['ssim'] - theirs):.2e}")
        self.assertLess(abs(ours["ssim"] - theirs), SSIM_TOLERANCE, label)
        mse = mean_squared_error(a.astype(np.float64), b.astype(np.float64))
        self.assertAlmostEqual(ours["rmse"], np.sqrt(mse), delta=1e-4, msg=label)
        if mse > 0:
            psnr = peak_signal_noise_ratio(a, b, data_range=255)
            self.assertAlmostEqual(ours["psnr"], psnr, delta=1e-4, msg=label)
        self.assertAlmostEqual(ours["max"], np.abs(a.astype(int) - b.astype(int)).max(),
                               delta=1e-3, msg=label)
        return ours["ssim"]

    def test_photographs(self):
        for label, a, b in degraded_pairs():
            ssim = self.check_pair(label, a, b)
            self.assertLess(ssim, 1.0, label)

    def test_facet_render_against_its_reference(self):
        subprocess.run([TOOL, "sphere-pair", self.path("flat.png"), self.path("ref.png")],
                       check=True)
        flat = np.asarray(Image.open(self.path("flat.png")).convert("RGB"))
        reference = np.asarray(Image.open(self.path("ref.png")).convert("RGB"))
        self.assertGreater(np.count_nonzero(reference), 1000, "the reference shows the sphere")
        ssim = self.check_pair("sphere flat vs ref", reference, flat)
        self.assertGreater(ssim, 0.5)

    def test_identical(self):
        photo = rgb(data.camera())[:64, :80]
        self.assertAlmostEqual(self.check_pair("identical", photo, photo), 1.0, delta=1e-12)


if __name__ == "__main__":
    if not TOOL:
        sys.exit("usage: test_ssim_skimage.py FACET_IMAGE_METRICS_TOOL")
    unittest.main()
