// body_compare_png A.png B.png [--max-mean D] [--max-bad-fraction F] [--pixel-threshold T]
// Compares two images of the same size: the mean absolute channel difference
// (0..255) and the fraction of pixels whose largest channel difference exceeds
// T. Exit 0 when both are within bounds, 1 when not, 2 on bad input.
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(
            stderr,
            "usage: body_compare_png A.png B.png [--max-mean D] [--max-bad-fraction F] [--pixel-threshold T]\n");
        return 2;
    }
    double max_mean = 2.0, max_bad = 0.01;
    int threshold = 32;
    for (int i = 3; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--max-mean"))
            max_mean = std::atof(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--max-bad-fraction"))
            max_bad = std::atof(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--pixel-threshold"))
            threshold = std::atoi(argv[i + 1]);
        else {
            std::fprintf(stderr, "body_compare_png: unknown option %s\n", argv[i]);
            return 2;
        }
    }
    int w[2], h[2], n[2];
    unsigned char* px[2];
    for (int k = 0; k < 2; ++k) {
        px[k] = stbi_load(argv[1 + k], &w[k], &h[k], &n[k], 4);
        if (!px[k]) {
            std::fprintf(stderr, "body_compare_png: %s: %s\n", argv[1 + k], stbi_failure_reason());
            return 2;
        }
    }
    if (w[0] != w[1] || h[0] != h[1]) {
        std::fprintf(stderr, "body_compare_png: sizes differ: %dx%d vs %dx%d\n", w[0], h[0], w[1], h[1]);
        return 1;
    }
    double sum = 0;
    long bad = 0;
    const long pixels = long(w[0]) * h[0];
    for (long p = 0; p < pixels; ++p) {
        int worst = 0;
        for (int c = 0; c < 4; ++c) {
            int d = std::abs(int(px[0][4 * p + c]) - int(px[1][4 * p + c]));
            sum += d;
            worst = d > worst ? d : worst;
        }
        bad += worst > threshold;
    }
    const double mean = sum / (4.0 * double(pixels));
    const double bad_fraction = double(bad) / double(pixels);
    std::printf("compare %s vs %s: %dx%d, mean abs diff %.3f (max %.3f), pixels off by >%d: %.4f%% (max %.4f%%)\n",
                argv[1], argv[2], w[0], h[0], mean, max_mean, threshold, 100 * bad_fraction, 100 * max_bad);
    stbi_image_free(px[0]);
    stbi_image_free(px[1]);
    return (mean <= max_mean && bad_fraction <= max_bad) ? 0 : 1;
}
