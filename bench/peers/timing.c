/* Times CasADi's generated `acceleration` (the header is given with -include):
 * best of 7 batches of 100000 calls at a fixed state, in ns per call.
 * Arguments: the sizes of the three inputs q, qdot, u. */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static double now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e9 + t.tv_nsec;
}

int main(int argc, char **argv) {
    casadi_int sizes[3], arg_n, res_n, iw_n, w_n;
    for (int i = 0; i < 3 && i + 1 < argc; i++) sizes[i] = atoi(argv[i + 1]);
    acceleration_work(&arg_n, &res_n, &iw_n, &w_n);
    casadi_real in[3][64], out[256], *w = malloc(sizeof(casadi_real) * (w_n + 1));
    casadi_int *iw = malloc(sizeof(casadi_int) * (iw_n + 1));
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < sizes[i]; k++) in[i][k] = 0.3 * (k + 1) / (i + 2.0);
    const casadi_real *arg[3] = {in[0], in[1], in[2]};
    casadi_real *res[1] = {out};
    volatile casadi_real sink = 0;
    double best = 1e300;
    for (int batch = 0; batch < 7; batch++) {
        double start = now();
        for (int call = 0; call < 100000; call++) {
            in[1][0] += 1e-12;
            acceleration(arg, res, iw, w, 0);
            sink += out[0];
        }
        double elapsed = (now() - start) / 100000;
        if (elapsed < best) best = elapsed;
    }
    printf("%f\n", best);
    free(w);
    free(iw);
    return 0;
}
