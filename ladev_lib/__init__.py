"""LADEV: language-driven testing and evaluation of vision-language-action policies.

The library is pure: no argv, no fixed paths. Stage scripts in ``stages/`` and
the ``ladev`` command line call into it.
"""

__version__ = "0.1.0"
