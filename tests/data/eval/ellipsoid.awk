# a closed UV ellipsoid with a bump, NU x NV samples; pose P bends it
BEGIN {
  NU = 48; NV = 24; pi = 3.141592653589793
  print "OFF"; print (NU * (NV - 1) + 2), (2 * NU * (NV - 1)), 0
  print 0, 0, 1.0 * (1 + 0.02 * P)
  for (j = 1; j < NV; j++) for (i = 0; i < NU; i++) {
    t = pi * j / NV; p = 2 * pi * i / NU
    x = 1.6 * sin(t) * cos(p); y = 1.0 * sin(t) * sin(p); z = 0.7 * cos(t)
    b = exp(-((x - 1.2)^2 + y^2) * 4); x += 0.4 * b
    x += 0.1 * P * z * z; y += 0.05 * P * x * x
    print x, y, z
  }
  print 0, 0, -0.7
  n = NU * (NV - 1) + 1
  for (i = 0; i < NU; i++) print 3, 0, 1 + i, 1 + (i + 1) % NU
  for (j = 0; j < NV - 2; j++) for (i = 0; i < NU; i++) {
    a = 1 + j * NU + i; b2 = 1 + j * NU + (i + 1) % NU; c = a + NU; d = b2 + NU
    print 3, a, c, b2; print 3, b2, c, d
  }
  for (i = 0; i < NU; i++) print 3, n, n - NU + (i + 1) % NU, n - NU + i
}
