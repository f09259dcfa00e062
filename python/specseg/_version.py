"""The package's version: the one place it is written on the Python side.

It follows the C library's (include/specseg/version.h, checked by tests/python/test_package.py), so a
package and a library built from the same commit carry the same number.
"""
__version__ = "0.2.0"
