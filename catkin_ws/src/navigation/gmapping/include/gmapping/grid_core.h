// The hot loops of slam_gmapping's particle filter, as a plain C ABI (loaded by the Python core
// through ctypes): scan registration into every particle's grid, and gmapping's hill-climbing scan
// matcher with its score / likelihood. No ROS, no globals; gm_optimize allocates
// one scratch buffer per call.
//
// Grids: n particles, each its own row-major h x w block of cells (row = y index; the blocks
// are separate allocations, so resampling shares or copies them per particle); cell (0, 0)'s
// lower-left corner at (ox, oy) [m]; delta [m/cell]. A cell holds uint16 hit and visit counts
// (fullness hits / visits; unknown: visits 0) and mx/my, the mean of the endpoints that hit it as
// offsets [m] from the cell's lower-left corner (gmapping's PointAccumulator), side by side so
// that the matcher reads one cell from one place. Poses are laser poses (x [m], y [m],
// theta [rad]) in the map frame, one per particle (n x 3).
#pragma once
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  uint16_t hits, visits;
  float mx, my;
} GmCell;  // 12 bytes, no padding (numpy: u2, u2, f4, f4)

typedef struct {
  int n, h, w;
  double ox, oy, delta;
  GmCell** cells;  // n pointers, each to h * w cells
} GmGrids;

typedef struct {
  int beams;             // number of readings
  const double* ranges;  // [m]
  const double* angles;  // [rad] in the laser frame
  const double* cos_a;   // cos / sin of the angles (precomputed once per scan)
  const double* sin_a;
  double max_range;   // readings beyond (or 0 / NaN) are dropped
  double max_urange;  // readings are clipped to this (clipped ones mark free space only)
} GmScan;

typedef struct {
  double sigma;            // endpoint matching sigma [m^2]
  int kernel;              // correspondence search half window [cells]
  double lsigma;           // likelihood sigma
  int lskip;               // use every (lskip + 1)-th beam
  double lstep, astep;     // initial hill-climbing steps [m], [rad]
  int iterations;          // refinements
  double fullness;         // cell fullness threshold for a hit (gmapping: 0.1)
  double null_likelihood;  // likelihood of a beam with no correspondence (gmapping: -0.5)
  double minimum_score;    // a match scoring <= this keeps the odometry pose
} GmMatcherParams;

// Registers the scan at poses[i] into grid i for every particle (free cells along the beam,
// a hit at the end of an unclipped beam). Returns 0, or -1 if a beam leaves the grid (the caller
// grows the grids first, so -1 means a bug).
int gm_integrate(GmGrids* g, const double* poses, const GmScan* scan);

// gmapping's score of one pose against grid i.
double gm_score(const GmGrids* g, int i, const double* pose, const GmScan* scan,
                const GmMatcherParams* p);

// Hill-climbing optimisation of poses[i] against grid i for every particle; writes the accepted
// poses to out_poses (n x 3: the optimised pose if its score > minimum_score, else the input pose),
// the match scores to out_scores (n) and the log likelihood of the accepted pose to out_likelihood
// (n).
void gm_optimize(const GmGrids* g, const double* poses, const GmScan* scan,
                 const GmMatcherParams* p, double* out_poses, double* out_scores,
                 double* out_likelihood);

// Log likelihood and score of pose against grid i (gmapping's likelihoodAndScore).
void gm_likelihood_and_score(const GmGrids* g, int i, const double* pose, const GmScan* scan,
                             const GmMatcherParams* p, double* likelihood, double* score);

#ifdef __cplusplus
}
#endif
