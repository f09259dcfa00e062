/* Numbers in text as C writes and reads them ('.' as the decimal point) whatever locale the host
 * program has set: a program that calls setlocale(LC_ALL, "") on a German desktop, or Python code that
 * calls locale.setlocale, would otherwise make strtod stop at the '.' of "1.5" and printf write "1,5"
 * into our files. Each function switches the calling thread's locale to "C" for the call alone
 * (uselocale: the thread's own, never the process's) and back. Messages are left in the caller's
 * locale. Not public API. */
#ifndef SS_C_LOCALE_H
#define SS_C_LOCALE_H

#include <stdarg.h>
#include <stdio.h>

/* strtod in the C locale */
double ssi_strtod_c(const char *s, char **end);

/* vsnprintf, snprintf, fprintf and sscanf in the C locale (the same returns) */
int ssi_vsnprintf_c(char *buf, size_t n, const char *fmt, va_list ap);
int ssi_snprintf_c(char *buf, size_t n, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
int ssi_fprintf_c(FILE *f, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
int ssi_sscanf_c(const char *s, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(scanf, 2, 3)))
#endif
    ;

#endif
