/* Built by run.cmake with `cc pc_check.c $(pkg-config --cflags --libs stipple)`: the installed
 * stipple.pc gives a C program the headers and the libraries. A missing file: STIPPLE_ERROR_IO. */
#include <runtime/stipple.h>
#include <stdio.h>

int main(void) {
    stipple_asset* asset = NULL;
    const stipple_result r = stipple_asset_load_file("/nonexistent/missing.stip", &asset);
    if (r != STIPPLE_ERROR_IO || asset != NULL) {
        fprintf(stderr, "expected STIPPLE_ERROR_IO, got %d\n", (int)r);
        return 1;
    }
    printf("%s\n", stipple_last_error());
    return 0;
}
