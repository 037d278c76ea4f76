/* Whitespace-separated numbers in text, parsed to packed float64 or int64.
 *
 * Mesh files (COLLADA float_array and <p>, OBJ) are mostly numbers in text, and parsing them was
 * the largest single cost of converting a mesh-heavy robot: numpy.fromstring(sep=" ") spends about
 * 200 ns per float on a 7-to-10-digit mesh number, this about 30 ns. The doubles are the ones a
 * correctly rounded parser gives, bit for bit: short decimals take Clinger's exact fast path, all
 * others PyOS_string_to_double (the parser behind float() and numpy.fromstring). Nothing here
 * imports numpy: the result is a bytearray the caller views with frombuffer.
 *
 * parse(text: str | bytes, integers: bool) -> bytearray
 *     Raises ValueError("bad token at N") with N the token's index when a token is not a number
 *     (or an integer that does not fit int64). Separators are the C locale's isspace characters,
 *     as numpy.fromstring(sep=" ") takes them.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <float.h>
#include <stdint.h>
#include <string.h>

static int is_space(char c) {
    return c == ' ' || c == '\n' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/* One decimal integer token [+-]?[0-9]+, exactly; 0 on success. */
static int parse_int(const char *s, const char *end, int64_t *out) {
    int negative = 0;
    if (s < end && (*s == '+' || *s == '-')) {
        negative = *s == '-';
        s++;
    }
    if (s == end) {
        return -1;
    }
    /* Accumulate as a negative number so INT64_MIN fits. */
    int64_t value = 0;
    for (; s < end; s++) {
        if (*s < '0' || *s > '9') {
            return -1;
        }
        int digit = *s - '0';
        if (value < (INT64_MIN + digit) / 10) {
            return -1;
        }
        value = value * 10 - digit;
    }
    if (!negative) {
        if (value == INT64_MIN) {
            return -1;
        }
        value = -value;
    }
    *out = value;
    return 0;
}

/* Powers of ten that are exact doubles (5^22 < 2^53). */
static const double exact_powers[] = {
    1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
    1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
};

/* Clinger's fast path: a decimal [+-]?digits[.digits][(e|E)[+-]?digits] whose digits make an
 * integer m <= 2^53 and whose power of ten e has |e| <= 22 is m * 10^e or m / 10^-e, one correctly
 * rounded IEEE operation on two exact doubles, so the same double a correctly rounded parser gives.
 * Mesh numbers (7 to 10 digits) nearly all qualify; 1 when the token is not such a number. */
static int parse_simple(const char *s, const char *end, double *out) {
#if FLT_EVAL_METHOD != 0
    /* Wider intermediates (x87) would round twice: leave every token to the exact parser. */
    return 1;
#endif
    int negative = 0;
    if (*s == '+' || *s == '-') {
        negative = *s == '-';
        s++;
    }
    uint64_t mantissa = 0;
    int digits = 0;      /* significant digits in mantissa (leading zeros skipped) */
    int any = 0;         /* whether the mantissa had a digit at all */
    int scale = 0;       /* digits after the point */
    for (; s < end && *s >= '0' && *s <= '9'; s++) {
        any = 1;
        if (mantissa == 0 && *s == '0') {
            continue;
        }
        if (++digits > 19) {
            return 1;
        }
        mantissa = mantissa * 10 + (uint64_t)(*s - '0');
    }
    if (s < end && *s == '.') {
        for (s++; s < end && *s >= '0' && *s <= '9'; s++) {
            any = 1;
            scale++;
            if (mantissa == 0 && *s == '0') {
                continue;
            }
            if (++digits > 19) {
                return 1;
            }
            mantissa = mantissa * 10 + (uint64_t)(*s - '0');
        }
    }
    if (!any) {
        return 1;
    }
    int exponent = 0;
    if (s < end && (*s == 'e' || *s == 'E')) {
        s++;
        int exponent_negative = 0;
        if (s < end && (*s == '+' || *s == '-')) {
            exponent_negative = *s == '-';
            s++;
        }
        if (s == end) {
            return 1;
        }
        for (; s < end && *s >= '0' && *s <= '9'; s++) {
            if (exponent > 1000) {
                return 1;
            }
            exponent = exponent * 10 + (*s - '0');
        }
        if (exponent_negative) {
            exponent = -exponent;
        }
    }
    if (s != end || mantissa > ((uint64_t)1 << 53)) {
        return 1;
    }
    int power = exponent - scale;
    double value = (double)mantissa;
    if (power < 0) {
        if (power < -22) {
            return 1;
        }
        value = value / exact_powers[-power];
    } else {
        if (power > 22) {
            return 1;
        }
        value = value * exact_powers[power];
    }
    *out = negative ? -value : value;
    return 0;
}

/* One float token as float() reads it (without underscores): the fast path, else
 * PyOS_string_to_double, the parser behind float() and numpy.fromstring; 0 on success. The token is
 * followed by a separator or the buffer's terminating NUL, so that parser stops at its end. */
static int parse_double(const char *s, const char *end, double *out) {
    if (parse_simple(s, end, out) == 0) {
        return 0;
    }
    char *stop = NULL;
    double value = PyOS_string_to_double(s, &stop, NULL);
    if (value == -1.0 && PyErr_Occurred()) {
        PyErr_Clear();
        return -1;
    }
    if (stop != end) {
        return -1;
    }
    if (value != value) {
        /* numpy reads "-nan" as the positive quiet NaN, as it reads "nan". */
        uint64_t bits = 0x7ff8000000000000ULL;
        memcpy(&value, &bits, 8);
    }
    *out = value;
    return 0;
}

static PyObject *parse(PyObject *self, PyObject *args) {
    PyObject *text;
    int integers;
    if (!PyArg_ParseTuple(args, "Op", &text, &integers)) {
        return NULL;
    }
    const char *data;
    Py_ssize_t size;
    if (PyUnicode_Check(text)) {
        data = PyUnicode_AsUTF8AndSize(text, &size);
        if (data == NULL) {
            return NULL;
        }
    } else if (PyBytes_Check(text)) {
        data = PyBytes_AS_STRING(text);
        size = PyBytes_GET_SIZE(text);
    } else {
        PyErr_SetString(PyExc_TypeError, "parse() takes str or bytes");
        return NULL;
    }
    /* At most one number per two bytes ("1 1 1"), plus one for text without a trailing separator. */
    Py_ssize_t capacity = size / 2 + 1;
    PyObject *out = PyByteArray_FromStringAndSize(NULL, capacity * 8);
    if (out == NULL) {
        return NULL;
    }
    char *cursor = PyByteArray_AS_STRING(out);
    const char *p = data;
    const char *end = data + size;
    Py_ssize_t count = 0;
    int bad = 0;
    while (1) {
        while (p < end && is_space(*p)) {
            p++;
        }
        if (p == end) {
            break;
        }
        const char *start = p;
        while (p < end && !is_space(*p)) {
            p++;
        }
        if (integers) {
            int64_t value;
            if (parse_int(start, p, &value) != 0) {
                bad = 1;
                break;
            }
            memcpy(cursor, &value, 8);
        } else {
            double value;
            if (parse_double(start, p, &value) != 0) {
                bad = 1;
                break;
            }
            memcpy(cursor, &value, 8);
        }
        cursor += 8;
        count++;
    }
    if (bad) {
        Py_DECREF(out);
        PyErr_Format(PyExc_ValueError, "bad token at %zd", count);
        return NULL;
    }
    if (PyByteArray_Resize(out, count * 8) != 0) {
        Py_DECREF(out);
        return NULL;
    }
    return out;
}

static PyMethodDef methods[] = {
    {"parse", parse, METH_VARARGS, "parse(text, integers) -> bytearray of packed float64 or int64"},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {
    PyModuleDef_HEAD_INIT, "_numtext", "Whitespace-separated numbers in text, parsed fast.", -1, methods,
};

PyMODINIT_FUNC PyInit__numtext(void) { return PyModule_Create(&module); }
