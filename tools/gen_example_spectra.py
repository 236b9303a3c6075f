#!/usr/bin/env python3
"""Example reflectance spectra in data/examples/: patches of the ColorChecker Classic as measured by
N. Ohta (colour-science dataset "ColorChecker N Ohta", 380-780 nm at 5 nm).

Usage: python3 tools/gen_example_spectra.py
"""
import os
import colour

OUT = os.path.join(os.path.dirname(__file__), "..", "data", "examples")
os.makedirs(OUT, exist_ok=True)
checker = colour.SDS_COLOURCHECKERS["ColorChecker N Ohta"]
for patch, fname in [("dark skin", "colorchecker_dark_skin.csv"), ("green", "colorchecker_green.csv"),
                     ("red", "colorchecker_red.csv"), ("blue", "colorchecker_blue.csv"),
                     ("white 9.5 (.05 D)", "colorchecker_white.csv")]:
    sd = checker[patch]
    with open(os.path.join(OUT, fname), "w") as f:
        f.write("# ColorChecker Classic patch '%s', reflectance, measured by N. Ohta\n" % patch)
        f.write("# (colour-science %s dataset 'ColorChecker N Ohta'); made by tools/gen_example_spectra.py\n"
                % colour.__version__)
        f.write("wavelength_nm,reflectance\n")
        for w, v in zip(sd.wavelengths, sd.values):
            f.write("%g,%r\n" % (w, float(v)))
print(sorted(os.listdir(OUT)))
