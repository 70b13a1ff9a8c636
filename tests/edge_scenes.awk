# edge_scenes.awk: writes N scenes with everything at or near the scene cube's edges (tests/faults.sh renders them).
# awk -v n=N -v seed=S -v dir=D -f tests/edge_scenes.awk: D/edge-001.scene ... Positions take
# the cube's faces (+-4096) most often, then the middle and points near the origin; radii the
# limits (1/128, 2048) and a few between; planes offsets of +-4096 and small ones, normals
# along the axes and the diagonals; lights of intensity up to 16, some near a sphere's surface.
function pick(list,   a, k) { k = split(list, a, " "); return a[1 + int(rand() * k)] }
function coord() { return pick("-4096 4096 -4096 4096 -4095.99 4095.99 -2048 2048 0 5.6 -5.6 0.3 8 -8 4096 -4096") }
function pos() { return coord() " " coord() " " coord() }
function normal(   v) { do v = pick("-1 0 1 0 1 3 -2") " " pick("-1 0 1 0 1 3 -2") " " pick("-1 0 1 0 1 3 -2"); while (v == "0 0 0"); return v }
BEGIN {
  srand(seed)
  for (s = 1; s <= n; s++) {
    f = sprintf("%s/edge-%03d.scene", dir, s)
    printf "# edge scene %d (seed %d)\ndepth %d\nbackground 0.2 0.3 0.4\nambient 0.1 0.1 0.1\n", s, seed, int(rand() * 9) > f
    do { eye = pos(); at = pos() } while (eye == at)
    printf "camera eye %s at %s up %s fov %s\n", eye, at, normal(), pick("10 50 120") > f
    print "material m diffuse 0.8 0.7 0.6 specular 1 shininess 1000" > f
    print "material mirror diffuse 0.1 0.1 0.1 specular 0.5 shininess 7 reflect 1" > f
    print "material glass diffuse 0 0 0 reflect 0.1 transmit 0.9 ior 3" > f
    print "material check diffuse 1 1 1 texture checker scale 0.5 color2 0 0 0 reflect 0.5" > f
    print "material stone texture marble octaves 8 scale 0.5 turbulence 16" > f
    nl = 1 + int(rand() * 4)
    centre = pos()
    for (l = 0; l < nl; l++) {
      lp = rand() < 0.3 ? centre : pos()
      if (rand() < 0.3) { # just above or below the first sphere's centre, inside the cube
        split(centre, c, " "); y = c[2] + pick("1 3 8 -8"); y = y > 4096 ? 4096 : y < -4096 ? -4096 : y
        lp = c[1] " " y " " c[3]
      }
      col = pick("16_16_16 1_1_1 16_0_16 0.5_0.5_0.5"); gsub("_", " ", col)
      printf "light l%d pos %s color %s\n", l, lp, col > f
    }
    no = 1 + int(rand() * 6)
    for (o = 0; o < no; o++) {
      mat = pick("m mirror glass check stone")
      if (rand() < 0.6)
        printf "sphere s%d material %s center %s radius %s\n", o, mat, o == 0 ? centre : pos(), pick("0.0078125 0.2 5.6 1000 2048 2048") > f
      else
        printf "plane p%d material %s normal %s offset %s\n", o, mat, normal(), pick("-4096 4096 4096 -4096 0 -20 20 8") > f
    }
    close(f)
  }
}
