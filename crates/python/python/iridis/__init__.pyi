from . import color as color
from . import diffraction as diffraction
from . import lab as lab
from . import render as render
from . import surface as surface
from . import thinfilm as thinfilm
from . import tmm as tmm
from .scan_report import demo as demo
from .scan_report import report as report

__version__: str
