"""rockcli: rocking and overturning of free-standing rigid blocks on rigid and isolated bases.

Implements Vassiliou & Makris (2012), "Analysis of the rocking response of rigid blocks standing
free on a seismically isolated base", Earthquake Engng Struct Dyn 41:177-196.

Importing this package is cheap: heavy dependencies (ObsPy, numba, pandas, matplotlib) are
imported by the submodules that need them.
"""

__version__ = "0.1.0"
