"""Reference values for iridis' AFM instrument readers, read by independent implementations.

Reads the real instrument files that tools/fetch_afm_samples.sh puts in $IRIDIS_AFM_SAMPLES (default
target/afm-samples) with AFMReader 0.0.7 (and the libraries it builds on: pySPM for Bruker, igor2 for
Igor waves, tifffile for JPK) and with gsffile for the .gsf written from the real .stp scan, and writes only
numbers to crates/surface/tests/fixtures/afm_reference.json: shape, pixel size, min/max/mean height (nm), a
few sample values (row 0 = the top row as AFMReader returns it) and the channel names. The files themselves
are never committed.

A Nanonis .sxm file: no package on PyPI that we found ships a real one (AFMReader, pySPM, nanonispy2, spym,
xarray-nanonis, nanonis-reader, nanonis, nanonis-load, g80sxm, sxm-converter were checked), and no
independent library writes one. This script therefore writes a small .sxm by the published layout
(crates/surface/tests/fixtures/nanonis_synthetic.sxm: 2 channels x forward/backward, 40 x 24 pixels,
scan direction up) and records what pySPM's independent SXM reader reads from it. It is synthetic, and
the reference says so.

Run: python3 -m venv /tmp/venv-afm && /tmp/venv-afm/bin/pip install AFMReader==0.0.7 gsffile==0.5.5 numpy
     tools/fetch_afm_samples.sh && /tmp/venv-afm/bin/python tools/gen_afm_fixtures.py
"""

import json
import os
import re
from pathlib import Path

import gsffile
import igor2
import numpy as np
import pySPM
import tifffile
from AFMReader import gwy, ibw, jpk, spm, stp, top

ROOT = Path(__file__).resolve().parent.parent
SAMPLES = Path(os.environ.get("IRIDIS_AFM_SAMPLES", ROOT / "target" / "afm-samples"))
FIXTURES = ROOT / "crates" / "surface" / "tests" / "fixtures"


def positions(rows, cols):
    return [
        (0, 0),
        (0, cols - 1),
        (rows - 1, 0),
        (rows - 1, cols - 1),
        (rows // 3, cols // 2),
        (rows // 2, cols // 7),
        (2 * rows // 3, 5 * cols // 6),
    ]


def summary(image, pixel_nm, reader, channel, **extra):
    image = np.asarray(image, dtype=np.float64)
    rows, cols = image.shape
    out = {
        "reader": reader,
        "channel": channel,
        "rows": rows,
        "cols": cols,
        "pixel_nm": float(pixel_nm),
        "min_nm": float(image.min()),
        "max_nm": float(image.max()),
        "mean_nm": float(image.mean()),
        "samples": [[r, c, float(image[r, c])] for r, c in positions(rows, cols)],
    }
    out.update(extra)
    return out


def roughness_numpy(image, pixel_nm):
    """Gwyddion-style statistics of the least-squares-plane-levelled image, by numpy alone.

    Sq, Sa, skewness, excess kurtosis, Sz; the ACF G(m, n) = sum z z' / ((R-|m|)(C-|n|)) through a zero-padded
    FFT, its radial average in annuli of one pixel, and the lag where that falls to G(0)/e.
    """
    z = np.asarray(image, dtype=np.float64)
    rows, cols = z.shape
    y, x = np.mgrid[0:rows, 0:cols]
    a = np.column_stack([np.ones(z.size), x.ravel(), y.ravel()])
    coef, *_ = np.linalg.lstsq(a, z.ravel(), rcond=None)
    z = z - (a @ coef).reshape(rows, cols)
    z = z - z.mean()
    sq = np.sqrt(np.mean(z**2))
    f = np.fft.fft2(z, s=(2 * rows, 2 * cols))
    g = np.real(np.fft.ifft2(np.abs(f) ** 2))
    hr, hc = rows // 2, cols // 2
    m = np.arange(-hr, hr + 1)
    n = np.arange(-hc, hc + 1)
    gm = g[np.ix_(m % (2 * rows), n % (2 * cols))]
    counts = np.outer(rows - np.abs(m), cols - np.abs(n))
    acf = gm / counts
    r = np.hypot(*np.meshgrid(m, n, indexing="ij"))
    idx = np.floor(r + 0.5).astype(int)
    nbins = min(hr, hc) + 1
    radial = np.array([acf[idx == i].mean() for i in range(nbins)])
    t = radial[0] / np.e
    tau = None
    for i in range(1, nbins):
        if radial[i] <= t:
            tau = pixel_nm * ((i - 1) + (radial[i - 1] - t) / (radial[i - 1] - radial[i]))
            break
    return {
        "sq_nm": float(sq),
        "sa_nm": float(np.mean(np.abs(z))),
        "skewness": float(np.mean(z**3) / sq**3),
        "excess_kurtosis": float(np.mean(z**4) / sq**4 - 3.0),
        "sz_nm": float(z.max() - z.min()),
        "correlation_length_nm": tau,
        "acf_lags_px": [[int(a_), int(b_), float(acf[hr + a_, hc + b_])] for a_, b_ in [(0, 0), (0, 5), (3, 0), (-7, 11)]],
    }


def spm_channels(path):
    scan = pySPM.Bruker(path)
    names = []
    for layer in scan.layers:
        line = layer.get(b"@2:Image Data")
        if line:
            names.append(line[0].decode("latin1").split('"')[1])
    return names


def ibw_channels(path):
    wave = igor2.binarywave.load(path)["wave"]
    return [label.decode() for label in wave["labels"][2] if label]


def jpk_channels(path):
    with tifffile.TiffFile(path) as tif:
        return [
            f"{p.tags[32848].value}_{'trace' if p.tags[32849].value == 0 else 'retrace'}" for p in tif.pages[1:]
        ]


def synthetic_sxm(path):
    """A small Nanonis scan by the SXM layout: header lines, :SCANIT_END:, 0x1A 0x04, big-endian f32."""
    cols, rows = 40, 24
    y, x = np.mgrid[0:rows, 0:cols]
    z_fwd = 1e-9 * (5.0 * np.sin(2 * np.pi * x / 10.0) + 0.3 * y)  # m
    z_bwd = z_fwd[:, ::-1] + 0.2e-9  # stored right to left
    cur_fwd = 1e-10 * (1.0 + 0.01 * x * y)
    cur_bwd = cur_fwd[:, ::-1]
    header = (
        ":NANONIS_VERSION:\n2\n"
        ":SCANIT_TYPE:\n              FLOAT            MSBFIRST\n"
        ":REC_DATE:\n 23.11.2026\n:REC_TIME:\n04:45:00\n"
        f":SCAN_PIXELS:\n       {cols}       {rows}\n"
        ":SCAN_RANGE:\n           4.000000E-7           2.400000E-7\n"
        ":SCAN_OFFSET:\n             0.000000E+0         0.000000E+0\n"
        ":SCAN_ANGLE:\n            0.000E+0\n"
        ":SCAN_DIR:\nup\n"
        ":DATA_INFO:\n"
        "\tChannel\tName\tUnit\tDirection\tCalibration\tOffset\n"
        "\t14\tZ\tm\tboth\t-3.480E-9\t0.000E+0\n"
        "\t0\tCurrent\tA\tboth\t1.000E+9\t0.000E+0\n"
        "\n:SCANIT_END:\n\n\n"
    )
    data = b"".join(a.astype(">f4").tobytes() for a in (z_fwd, z_bwd, cur_fwd, cur_bwd))
    path.write_bytes(header.encode("ascii") + b"\x1a\x04" + data)


def main():
    ref = {"source": "AFMReader 0.0.7 sdist tests/resources (fetched by tools/fetch_afm_samples.sh)"}
    f = SAMPLES / "sample_0.spm"
    image, px = spm.load_spm(f, channel="Height")
    ref["spm"] = summary(image, px, "AFMReader.spm.load_spm (pySPM 0.6.3)", "Height", channels=spm_channels(f))
    f = SAMPLES / "sample_0.ibw"
    image, px = ibw.load_ibw(f, channel="HeightTracee")
    ref["ibw"] = summary(image, px, "AFMReader.ibw.load_ibw (igor2)", "HeightTracee", channels=ibw_channels(f))
    f = SAMPLES / "sample_0.jpk"
    image, px = jpk.load_jpk(f, channel="height_trace")
    ref["jpk"] = summary(image, px, "AFMReader.jpk.load_jpk (tifffile)", "height_trace", channels=jpk_channels(f))
    f = SAMPLES / "sample_0.gwy"
    image, px = gwy.load_gwy(f, channel="ZSensor")
    ref["gwy"] = summary(image, px, "AFMReader.gwy.load_gwy", "ZSensor", roughness=roughness_numpy(image, px))
    f = SAMPLES / "sample_0.stp"
    stp_image, px = stp.load_stp(f)
    ref["stp"] = summary(stp_image, px, "AFMReader.stp.load_stp", "Topography")
    # .top: AFMReader rescales the int16 codes to [0, int(Z Amplitude)] (its regex keeps the integer part of
    # "Z Amplitude: 59.7449 nm"); the WSxM convention scales codes by Z Amplitude / (Maximum - Minimum) of the
    # header, which reproduces the .stp twin that WSxM itself wrote. Both are recorded.
    f = SAMPLES / "sample_0.top"
    top_image, px = top.load_top(f)
    header = f.read_bytes()[:4000].decode("latin-1")
    z_amp = float(re.search(r"Z Amplitude: ([\d.]+) nm", header).group(1))
    hi = float(re.search(r"\n\s*Maximum: (-?\d+)", header).group(1))
    lo = float(re.search(r"\n\s*Minimum: (-?\d+)", header).group(1))
    ref["top"] = summary(
        top_image,
        px,
        "AFMReader.top.load_top",
        "Topography",
        z_amplitude_nm=z_amp,
        afmreader_z_amplitude_nm=float(int(z_amp)),
        code_min=lo,
        code_max=hi,
        code_step_nm=z_amp / (hi - lo),
        stp_twin_samples=ref["stp"]["samples"],
    )
    f = SAMPLES / "sample_0.gsf"
    data, meta = gsffile.read_gsf(f)
    ref["gsf"] = summary(
        np.asarray(data, dtype=np.float64) * 1e9,
        meta["XReal"] * 1e9 / data.shape[1],
        "gsffile 0.5.5 read_gsf (file written by gsffile from sample_0.stp)",
        meta.get("Title", ""),
    )
    sxm_path = FIXTURES / "nanonis_synthetic.sxm"
    synthetic_sxm(sxm_path)
    scan = pySPM.SXM(str(sxm_path))
    entries = {}
    for name in ("Z", "Current"):
        for direction in ("forward", "backward"):
            stored = np.asarray(scan.get_channel(name, direction=direction).pixels, dtype=np.float64)
            rows, cols = stored.shape
            entries[f"{name}_{direction}"] = {
                "rows": rows,
                "cols": cols,
                # As stored (pySPM does not reorient): row 0 is the first line scanned.
                "stored_samples": [[r, c, float(stored[r, c])] for r, c in positions(rows, cols)],
            }
    ref["sxm"] = {
        "reader": "pySPM 0.6.3 SXM (synthetic file written by this script, see its docstring)",
        "pixel_nm": scan.size["real"]["x"] * 1e9 / scan.size["pixels"]["x"],
        "scan_dir": "up",
        "channels": entries,
    }
    out = FIXTURES / "afm_reference.json"
    out.write_text(json.dumps(ref, indent=1) + "\n")
    print(f"wrote {out} and {sxm_path}")


if __name__ == "__main__":
    main()
