/* The library's one set of 4x4 matrix helpers (internal): double precision, column-major as
 * OpenGL stores them (row r, column c at index 4 c + r). The scene's transforms and the camera are
 * built in double; the GL renderer multiplies them here and converts the product to float once,
 * for the uniform. */
#ifndef LUCENT_BASE_MAT4_H
#define LUCENT_BASE_MAT4_H

/* dest = a b; dest may be a or b. */
void lucent_mat4_mul(const double a[16], const double b[16], double dest[16]);

/* The float copy of m that a GL uniform takes. */
void lucent_mat4_to_float(const double m[16], float dest[16]);

#endif
