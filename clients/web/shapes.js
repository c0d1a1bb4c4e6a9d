// shapes.js: the built-in synthetic examples, made in the page so the viewer
// works without any data: a hand (flattened-ellipsoid palm, five capsule
// fingers in a fan) and a dumbbell (two spheres joined by a thin tube), the
// shapes of tests/support/shapes.c.  Deterministic (seeded), roughly uniform on
// the surface; points inside another primitive are dropped.
// Each returns a Float32Array #P*3.

function randomSource(seed) {
  let s = seed >>> 0;
  return () => {
    s ^= s << 13;
    s ^= s >>> 17;
    s ^= s << 5;
    return (s >>> 0) / 4294967296;
  };
}

function unitSpherePoint(rand) {
  const z = 2 * rand() - 1;
  const phi = 2 * Math.PI * rand();
  const r = Math.sqrt(1 - z * z);
  return [r * Math.cos(phi), r * Math.sin(phi), z];
}

const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const axpy = (a, s, b) => [a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]];

function sphere(centre, r) {
  return {
    area: 4 * Math.PI * r * r,
    sample: (rand) => axpy(centre, r, unitSpherePoint(rand)),
    inside: (x, m) => dot(sub(x, centre), sub(x, centre)) < (r - m) * (r - m),
  };
}

function capsule(a, b, r) {
  const axis = sub(b, a);
  const len = Math.sqrt(dot(axis, axis));
  const d = axis.map((v) => v / len);
  const h = Math.abs(d[0]) > 0.9 ? [0, 1, 0] : [1, 0, 0];
  const e1 = [d[1] * h[2] - d[2] * h[1], d[2] * h[0] - d[0] * h[2], d[0] * h[1] - d[1] * h[0]];
  const n1 = Math.sqrt(dot(e1, e1));
  e1.forEach((v, i) => (e1[i] = v / n1));
  const e2 = [d[1] * e1[2] - d[2] * e1[1], d[2] * e1[0] - d[0] * e1[2], d[0] * e1[1] - d[1] * e1[0]];
  const side = 2 * Math.PI * r * len;
  const area = side + 4 * Math.PI * r * r;
  return {
    area,
    sample(rand) {
      if (rand() * area < side) {
        const t = rand() * len;
        const phi = 2 * Math.PI * rand();
        return axpy(axpy(axpy(a, t, d), r * Math.cos(phi), e1), r * Math.sin(phi), e2);
      }
      const u = unitSpherePoint(rand);
      return axpy(dot(u, d) >= 0 ? b : a, r, u);
    },
    inside(x, m) {
      const t = Math.min(len, Math.max(0, dot(sub(x, a), d)));
      const q = sub(x, axpy(a, t, d));
      return dot(q, q) < (r - m) * (r - m);
    },
  };
}

function ellipsoid(r) {
  const [bc, ac, ab] = [r[1] * r[2], r[0] * r[2], r[0] * r[1]];
  const most = Math.max(bc, ac, ab);
  const p = 1.6;
  const ap = Math.pow(ab, p), bp = Math.pow(ac, p), cp = Math.pow(bc, p);
  return {
    area: 4 * Math.PI * Math.pow((ap + bp + cp) / 3, 1 / p),
    sample(rand) {
      for (;;) {
        const u = unitSpherePoint(rand);
        const stretch = Math.sqrt(bc * bc * u[0] * u[0] + ac * ac * u[1] * u[1] + ab * ab * u[2] * u[2]);
        if (rand() * most <= stretch) return [r[0] * u[0], r[1] * u[1], r[2] * u[2]];
      }
    },
    inside: (x, m) => x.reduce((s, v, i) => s + (v / r[i]) * (v / r[i]), 0) < 1 - m,
  };
}

function sampleUnion(prims, density, seed) {
  const rand = randomSource(seed);
  const out = [];
  prims.forEach((prim, i) => {
    const want = Math.round(density * prim.area);
    for (let s = 0; s < want; s++) {
      const x = prim.sample(rand);
      if (prims.some((o, j) => j !== i && o.inside(x, 1e-9))) continue;
      out.push(x[0], x[1], x[2]);
    }
  });
  return Float32Array.from(out);
}

// density: points per unit area (the hand is about 10 units long).
export function makeHand(density = 82) {
  const palm = [1.6, 2.0, 0.6];
  const angles = [-70, -30, -5, 20, 45];
  const lengths = [1.6, 2.4, 2.8, 2.6, 2.0];
  const radii = [0.34, 0.3, 0.3, 0.3, 0.27];
  const prims = [ellipsoid(palm)];
  angles.forEach((deg, f) => {
    const th = (deg * Math.PI) / 180;
    const d = [Math.sin(th), Math.cos(th), 0];
    const rim = 1 / Math.sqrt((d[0] * d[0]) / (palm[0] * palm[0]) + (d[1] * d[1]) / (palm[1] * palm[1]));
    const base = 0.75 * rim, tip = rim + lengths[f];
    prims.push(capsule([base * d[0], base * d[1], 0], [tip * d[0], tip * d[1], 0], radii[f]));
  });
  return sampleUnion(prims, density, 0x9e3779b9);
}

export function makeDumbbell(density = 105) {
  const prims = [sphere([-2, 0, 0], 1), sphere([2, 0, 0], 1), capsule([-2, 0, 0], [2, 0, 0], 0.25)];
  return sampleUnion(prims, density, 0x2545f491);
}
