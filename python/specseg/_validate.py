"""Checked conversions of Python / NumPy inputs to what the C library takes.

The library's integers are C ints (int32) and its options plain doubles. A bare
``np.asarray(x, dtype=np.int32)`` or ``ctypes.c_int(x)`` wraps out-of-range values silently
(2**32 becomes 0), truncates 1.7 to 1 and turns NaN into an arbitrary integer; these helpers refuse
such input with a ValueError (wrong values) or TypeError (wrong kinds) that names the argument.
"""
import math
import numbers
import operator

import numpy as np

INT32_MIN = -(2 ** 31)
INT32_MAX = 2 ** 31 - 1


def _where(a, flat_index):
    """'[i]' or '[i, j]' for the entry at flat_index of array a."""
    if a.ndim <= 1:
        return "[%d]" % flat_index
    return "[%s]" % ", ".join(str(int(i)) for i in np.unravel_index(flat_index, a.shape))


def _range_text(lo, hi):
    if (lo, hi) == (INT32_MIN, INT32_MAX):
        return "the int32 range %d..%d" % (lo, hi)
    return "%d..%d" % (lo, hi) if lo <= hi else "an empty range (%d..%d)" % (lo, hi)


def _as_int_array(x, name, lo, hi, dtype):
    a = np.asarray(x)
    kind = a.dtype.kind
    if kind == "b":
        raise TypeError("%s must be integers, not booleans (for a mask use np.flatnonzero(mask))" % name)
    if kind == "O":
        # e.g. Python ints beyond 64 bits, or a mixture: check each entry as a scalar
        flat = a.ravel()
        out = np.empty(flat.size, dtype)
        for i, v in enumerate(flat):
            out[i] = _as_int_scalar(v, "%s%s" % (name, _where(a, i)), lo, hi)
        return out.reshape(a.shape)
    if kind == "f":
        if a.size:
            bad = ~np.isfinite(a)
            if bad.any():
                i = int(np.flatnonzero(bad.ravel())[0])
                raise ValueError("%s%s is %r: expected an integer" % (name, _where(a, i), float(a.ravel()[i])))
            frac = a != np.trunc(a)
            if frac.any():
                i = int(np.flatnonzero(frac.ravel())[0])
                raise ValueError("%s%s is %r: expected an integer" % (name, _where(a, i), float(a.ravel()[i])))
    elif kind not in "iu":
        raise TypeError("%s must be an array of integers (got dtype %s)" % (name, a.dtype))
    if a.size:
        flat = a.ravel()
        imin, imax = int(np.argmin(flat)), int(np.argmax(flat))
        for i in (imin, imax):
            v = int(flat[i])
            if v < lo or v > hi:
                raise ValueError("%s%s = %d is outside %s" % (name, _where(a, i), v, _range_text(lo, hi)))
    return np.ascontiguousarray(a, dtype=dtype)


def as_int32_array(x, name, lo=INT32_MIN, hi=INT32_MAX):
    """`x` as a C-contiguous int32 array of the same shape, every entry checked to lie in lo..hi.

    Parameters
    ----------
    x : array_like of int
        Integer array of any shape. Floating-point arrays are accepted when every entry is a whole
        number (e.g. from ``np.loadtxt``); no copy when it already is C-contiguous int32.
    name : str
        What `x` is, for the error messages (e.g. ``"sources"``).
    lo, hi : int, optional
        Inclusive bounds, within the int32 range (the default).

    Returns
    -------
    numpy.ndarray of int32
        Same shape as `x`.

    Raises
    ------
    ValueError
        An entry outside lo..hi (in particular outside the int32 range), a fractional or non-finite
        entry of a floating-point array.
    TypeError
        A boolean array or one that is not numeric.
    """
    lo, hi = max(int(lo), INT32_MIN), min(int(hi), INT32_MAX)
    return _as_int_array(x, name, lo, hi, np.int32)


def as_uint8_array(x, name):
    """`x` as a C-contiguous uint8 array (colours), every entry checked to lie in 0..255.

    Parameters
    ----------
    x : array_like of int
        Array of any shape; floating-point input must hold whole numbers.
    name : str
        What `x` is, for the error messages.

    Returns
    -------
    numpy.ndarray of uint8
        Same shape as `x`.

    Raises
    ------
    ValueError
        An entry outside 0..255, or fractional / non-finite.
    TypeError
        A boolean or non-numeric array.
    """
    a = np.asarray(x)
    if a.dtype == np.uint8:
        return np.ascontiguousarray(a)
    return _as_int_array(a, name, 0, 255, np.uint8)


def _as_int_scalar(x, name, lo, hi):
    if isinstance(x, (bool, np.bool_)):
        raise TypeError("%s must be an integer, not a boolean" % name)
    if isinstance(x, numbers.Integral) or (isinstance(x, np.ndarray) and x.ndim == 0 and x.dtype.kind in "iu"):
        v = operator.index(x)
    elif isinstance(x, numbers.Real) and not isinstance(x, (str, bytes)):
        f = float(x)
        if not math.isfinite(f) or not f.is_integer():
            raise ValueError("%s is %r: expected an integer" % (name, f))
        v = int(f)
    else:
        raise TypeError("%s must be an integer (got %s)" % (name, type(x).__name__))
    if v < lo or v > hi:
        raise ValueError("%s = %d is outside %s" % (name, v, _range_text(lo, hi)))
    return v


def as_int32(x, name, lo=INT32_MIN, hi=INT32_MAX):
    """`x` as a Python int checked to lie in lo..hi (inclusive, within the int32 range).

    Parameters
    ----------
    x : int
        An integer (Python or NumPy); a float is accepted when it is a whole number.
    name : str
        What `x` is, for the error messages.
    lo, hi : int, optional
        Inclusive bounds, within the int32 range (the default).

    Returns
    -------
    int

    Raises
    ------
    ValueError
        Outside lo..hi, fractional or non-finite.
    TypeError
        Not a number, or a boolean.
    """
    lo, hi = max(int(lo), INT32_MIN), min(int(hi), INT32_MAX)
    return _as_int_scalar(x, name, lo, hi)


def _is_real_scalar(x):
    if isinstance(x, (bool, np.bool_, str, bytes)):
        return False
    if isinstance(x, numbers.Real):
        return True
    return isinstance(x, np.ndarray) and x.ndim == 0 and x.dtype.kind in "iuf"


def as_float(x, name, allow_inf=False, positive=False):
    """`x` as a Python float, refusing NaN (always), infinities (unless allow_inf) and, with
    positive=True, values <= 0.

    Parameters
    ----------
    x : float
        A real number (Python or NumPy).
    name : str
        What `x` is, for the error messages.
    allow_inf : bool, optional
        Accept +inf / -inf (where the option documents what an infinity means).
    positive : bool, optional
        Require x > 0.

    Returns
    -------
    float

    Raises
    ------
    ValueError
        NaN, an infinity that is not allowed, or x <= 0 with positive=True.
    TypeError
        Not a real number (strings, complex numbers, booleans, None).
    """
    if not _is_real_scalar(x):
        raise TypeError("%s must be a real number (got %s)" % (name, type(x).__name__))
    f = float(x)
    if math.isnan(f):
        raise ValueError("%s is NaN" % name)
    if math.isinf(f) and not allow_inf:
        raise ValueError("%s must be finite (got %r)" % (name, f))
    if positive and not f > 0:
        raise ValueError("%s must be positive (got %r)" % (name, f))
    return f


def as_float64_array(x, name, finite=False):
    """`x` as a C-contiguous float64 array; with finite=True NaN / inf entries are refused.

    Parameters
    ----------
    x : array_like of float
        Real array of any shape.
    name : str
        What `x` is, for the error messages.
    finite : bool, optional
        Refuse non-finite entries.

    Returns
    -------
    numpy.ndarray of float64
        Same shape as `x`.

    Raises
    ------
    ValueError
        A non-finite entry with finite=True.
    TypeError
        A complex, boolean or non-numeric array.
    """
    a = np.asarray(x)
    if a.dtype.kind not in "iufO":
        raise TypeError("%s must be an array of real numbers (got dtype %s)" % (name, a.dtype))
    try:
        a = np.ascontiguousarray(a, dtype=np.float64)
    except (TypeError, ValueError) as e:
        raise TypeError("%s must be an array of real numbers (%s)" % (name, e)) from None
    if finite and a.size:
        bad = ~np.isfinite(a)
        if bad.any():
            i = int(np.flatnonzero(bad.ravel())[0])
            raise ValueError("%s%s is %r: expected a finite number" % (name, _where(a, i), float(a.ravel()[i])))
    return a
