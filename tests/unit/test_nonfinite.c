/* test_nonfinite.c: the renderer's guard discards exactly the non-finite reservoirs and radiance
 * values, empties those reservoirs keeping a finite confidence, and counts them. */
#include <math.h>
#include <string.h>

#include "methods/restir_di/di_sample.h"
#include "methods/restir_pt/restir_pt.h"
#include "render/nonfinite.h"
#include "test_util.h"

int main(void)
{
    struct di_reservoir di[4];
    memset(di, 0, sizeof di);
    for (int i = 0; i < 4; i++) {
        di[i].y.tri = 7;
        di[i].W = 1.0f;
        di[i].target = 2.0f;
        di[i].c = 3.0f;
    }
    di[1].W = NAN;
    di[2].target = INFINITY;
    di[3].c = NAN;
    EXPECT(nonfinite_discard_di(di, 4) == 3, "three bad DI reservoirs");
    EXPECT(di[0].y.tri == 7 && di[0].W == 1.0f, "a finite reservoir is kept as it is");
    EXPECT(di[1].y.tri < 0 && di[1].W == 0.0f && di[1].c == 3.0f, "W NaN: emptied, confidence kept");
    EXPECT(di[2].y.tri < 0 && di[2].c == 3.0f, "target infinite: emptied");
    EXPECT(di[3].y.tri < 0 && di[3].c == 0.0f, "confidence NaN: emptied with confidence 0");
    EXPECT(nonfinite_discard_di(di, 4) == 0, "nothing left to discard");

    struct pt_reservoir pt[2];
    memset(pt, 0, sizeof pt);
    pt[0].y.length = pt[1].y.length = 3;
    pt[0].W = pt[1].W = 1.0f;
    pt[1].W = -INFINITY;
    EXPECT(nonfinite_discard_pt(pt, 2) == 1 && pt[0].y.length == 3 && pt[1].y.length == 0, "PT reservoirs");

    float rgb[6] = {1.0f, NAN, 2.0f, INFINITY, -INFINITY, 0.5f};
    EXPECT(nonfinite_discard_rgb(rgb, 2) == 3, "three bad channels");
    EXPECT(rgb[0] == 1.0f && rgb[1] == 0.0f && rgb[3] == 0.0f && rgb[4] == 0.0f && rgb[5] == 0.5f,
           "bad channels zeroed, the others kept");
    return test_finish();
}
