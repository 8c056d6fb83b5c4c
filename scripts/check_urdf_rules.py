#!/usr/bin/env python3
"""Check biped URDFs against the rules of steplearn's URDF loader, independently of it.

    python3 scripts/check_urdf_rules.py FILE.urdf...          # report, exit 1 if any refused
    python3 scripts/check_urdf_rules.py --expect-refused F... # exit 1 if any is accepted

A second opinion written from the loader's rules (not from its code), in plain Python 3
with no dependencies, used to validate robots/*.urdf and tests/robots/**.urdf:

  * the XML parses; every joint names defined links; no link is the child of two joints;
    one root (the trunk); no loops;
  * every number is finite; masses positive; inertias positive definite and satisfying the
    triangle inequality; links without <inertial> are massless;
  * on each side (left = +y in the zero pose) the lowest body (a link with the links fixed
    to it) ends a leg whose path from the trunk has exactly six revolute/continuous joints
    with world axes, in order, z x y y y x (either sign); no fixed joint, lower == upper
    limit or mimic inside that chain;
  * straight vertical legs (sagittal offsets up to 3 cm, lateral up to 5 mm), hip roll and
    pitch axes crossing, ankle pitch and roll axes crossing;
  * the foot sole is the lowest axis-aligned <box> collision of the foot body;
  * package:// meshes resolve through ROS_PACKAGE_PATH or the directories above the file;
  * the centre of mass in a stance with the knees bent by 0.3 rad lies inside the support
    polygon of the two soles.

Each refusal names the element (link or joint) at fault.
"""
import math
import os
import sys
import xml.etree.ElementTree as ET

EXPECTED = ['z', 'x', 'y', 'y', 'y', 'x']
NAMES = ['hip yaw', 'hip roll', 'hip pitch', 'knee', 'ankle pitch', 'ankle roll']
BEND = 0.3  # knee bend of the stance used for the centre-of-mass test, rad


class Refused(Exception):
    def __init__(self, element, why):
        super().__init__('%s: %s' % (element, why))
        self.element = element


# ---- small linear algebra -------------------------------------------------------------
def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def apply(r, v):
    return [sum(r[i][k] * v[k] for k in range(3)) for i in range(3)]


def add(a, b):
    return [x + y for x, y in zip(a, b)]


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def norm(a):
    return math.sqrt(dot(a, a))


def rpy_matrix(r, p, y):
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    rx = [[1, 0, 0], [0, cr, -sr], [0, sr, cr]]
    ry = [[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]]
    rz = [[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]]
    return matmul(rz, matmul(ry, rx))


def axis_angle(u, q):
    x, y, z = u
    c, s, t = math.cos(q), math.sin(q), 1 - math.cos(q)
    return [[t * x * x + c, t * x * y - s * z, t * x * z + s * y],
            [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
            [t * x * z - s * y, t * y * z + s * x, t * z * z + c]]


I3 = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]


# ---- parsing ----------------------------------------------------------------------------
def numbers(text, n, element, what):
    try:
        vals = [float(t) for t in (text or '').split()]
    except ValueError:
        raise Refused(element, '%s %r is not numeric' % (what, text))
    if len(vals) != n:
        raise Refused(element, '%s %r needs %d numbers' % (what, text, n))
    if not all(math.isfinite(v) for v in vals):
        raise Refused(element, '%s %r is not finite' % (what, text))
    return vals


def origin(el, owner):
    o = el.find('origin') if el is not None else None
    if o is None:
        return [0, 0, 0], I3
    xyz = numbers(o.get('xyz', '0 0 0'), 3, owner, 'origin xyz')
    rpy = numbers(o.get('rpy', '0 0 0'), 3, owner, 'origin rpy')
    return xyz, rpy_matrix(*rpy)


class Robot:
    def __init__(self, path):
        self.path = path
        try:
            root = ET.parse(path).getroot()
        except ET.ParseError as e:
            raise Refused('XML', 'does not parse: %s' % e)
        self.links = {}
        for l in root.findall('link'):
            name = l.get('name')
            if name in self.links:
                raise Refused(name, 'link defined twice')
            self.links[name] = l
        self.joints = {}
        self.parent_joint = {}
        self.children = {n: [] for n in self.links}
        for j in root.findall('joint'):
            name = j.get('name')
            p, c = j.find('parent').get('link'), j.find('child').get('link')
            for end in (p, c):
                if end not in self.links:
                    raise Refused(name, 'names link %r, which is not defined' % end)
            if c in self.parent_joint:
                raise Refused(c, 'is the child of two joints (%s, %s)' % (self.parent_joint[c], name))
            self.joints[name] = j
            self.parent_joint[c] = name
            self.children[p].append(name)
        roots = [n for n in self.links if n not in self.parent_joint]
        if len(roots) != 1:
            raise Refused(','.join(roots) or 'robot', 'needs exactly one root link, found %d' % len(roots))
        self.root = roots[0]
        self.check_numbers()
        self.zero = self.fk({})
        if len(self.zero) != len(self.links):
            lost = sorted(set(self.links) - set(self.zero))
            raise Refused(lost[0], 'not reachable from the root (a loop)')

    def joint_info(self, name):
        j = self.joints[name]
        xyz, rot = origin(j, name)
        a = j.find('axis')
        axis = numbers(a.get('xyz'), 3, name, 'axis') if a is not None else [1, 0, 0]
        return j.get('type'), j.find('parent').get('link'), j.find('child').get('link'), xyz, rot, axis

    def check_numbers(self):
        for name, l in self.links.items():
            inert = l.find('inertial')
            if inert is not None:
                origin(inert, name)
                m = numbers(inert.find('mass').get('value'), 1, name, 'mass')[0]
                if not m > 0:
                    raise Refused(name, 'mass %g is not positive' % m)
                i = inert.find('inertia')
                v = {k: numbers(i.get(k, '0'), 1, name, k)[0] for k in ('ixx', 'ixy', 'ixz', 'iyy', 'iyz', 'izz')}
                mat = [[v['ixx'], v['ixy'], v['ixz']], [v['ixy'], v['iyy'], v['iyz']], [v['ixz'], v['iyz'], v['izz']]]
                d2 = mat[0][0] * mat[1][1] - mat[0][1] ** 2
                d3 = (mat[0][0] * (mat[1][1] * mat[2][2] - mat[1][2] ** 2)
                      - mat[0][1] * (mat[0][1] * mat[2][2] - mat[1][2] * mat[0][2])
                      + mat[0][2] * (mat[0][1] * mat[1][2] - mat[1][1] * mat[0][2]))
                if not (mat[0][0] > 0 and d2 > 0 and d3 > 0):
                    raise Refused(name, 'inertia is not positive definite')
                a, b, c = v['ixx'], v['iyy'], v['izz']
                if a + b < c or b + c < a or a + c < b:
                    raise Refused(name, 'inertia breaks the triangle inequality (%g %g %g)' % (a, b, c))
            for el in l.iter():
                for key in ('size', 'radius', 'length'):
                    if el.tag in ('box', 'sphere', 'cylinder', 'capsule') and el.get(key) is not None:
                        vals = numbers(el.get(key), 3 if key == 'size' else 1, name, el.tag + ' ' + key)
                        if min(vals) <= 0:
                            raise Refused(name, '%s %s not positive' % (el.tag, key))
                if el.tag == 'mesh':
                    self.resolve_mesh(el.get('filename'), name)
            for coll in l.findall('collision'):
                origin(coll, name)
        for name in self.joints:
            self.joint_info(name)
            lim = self.joints[name].find('limit')
            if lim is not None:
                for k in ('lower', 'upper', 'effort', 'velocity'):
                    if lim.get(k) is not None:
                        numbers(lim.get(k), 1, name, 'limit ' + k)

    def resolve_mesh(self, fn, owner):
        here = os.path.dirname(os.path.abspath(self.path))
        if fn.startswith('package://'):
            pkg, rest = fn[len('package://'):].split('/', 1)
            bases = [p for p in os.environ.get('ROS_PACKAGE_PATH', '').split(':') if p]
            d = here
            while True:
                bases.append(d)
                if os.path.dirname(d) == d:
                    break
                d = os.path.dirname(d)
            for b in bases:
                for cand in (os.path.join(b, pkg, rest), os.path.join(b, rest) if os.path.basename(b) == pkg else None):
                    if cand and os.path.isfile(cand):
                        return cand
            raise Refused(owner, 'mesh %s does not resolve' % fn)
        p = fn[len('file://'):] if fn.startswith('file://') else os.path.join(here, fn)
        if not os.path.isfile(p):
            raise Refused(owner, 'mesh %s does not exist' % fn)
        return p

    def fk(self, q):
        """World pose (position, rotation) of every link frame for joint angles q."""
        poses = {self.root: ([0, 0, 0], I3)}
        stack = [self.root]
        while stack:
            l = stack.pop()
            p, r = poses[l]
            for jn in self.children[l]:
                typ, _, child, xyz, rot, axis = self.joint_info(jn)
                if child in poses:
                    continue
                cp, cr = add(p, apply(r, xyz)), matmul(r, rot)
                if jn in q:
                    if typ == 'prismatic':
                        cp = add(cp, apply(cr, [a * q[jn] for a in axis]))
                    else:
                        n = norm(axis)
                        cr = matmul(cr, axis_angle([a / n for a in axis], q[jn]))
                poses[child] = (cp, cr)
                stack.append(child)
        return poses

    # ---- structure -----------------------------------------------------------------------
    def body_of(self, link):
        """The link that `link` is merged into (walking up through fixed joints)."""
        while link in self.parent_joint:
            j = self.joints[self.parent_joint[link]]
            if j.get('type') != 'fixed':
                return link
            link = j.find('parent').get('link')
        return link

    def group(self, body):
        out, stack = [body], [body]
        while stack:
            l = stack.pop()
            for jn in self.children[l]:
                j = self.joints[jn]
                if j.get('type') == 'fixed':
                    c = j.find('child').get('link')
                    out.append(c)
                    stack.append(c)
        return out

    def world_axis(self, jn, poses):
        typ, parent, child, xyz, rot, axis = self.joint_info(jn)
        r = poses[child][1]
        a = apply(r, axis)
        return [x / norm(a) for x in a]

    def chain(self, link):
        js = []
        while link in self.parent_joint:
            jn = self.parent_joint[link]
            js.append(jn)
            link = self.joints[jn].find('parent').get('link')
        return list(reversed(js))

    def legs(self):
        trunk_group = set(self.group(self.root))
        bodies = {self.body_of(l) for l in self.links} - {self.root}
        legs = {}
        for side, sign in (('left', 1), ('right', -1)):
            cands = []
            for b in bodies:
                if b in trunk_group:
                    continue
                lowest = min(self.zero[l][0][2] for l in self.group(b))
                if sign * self.zero[b][0][1] > 1e-6:
                    # ties (ankle pitch and roll at one point) go to the deeper link
                    cands.append((round(lowest, 6), -len(self.chain(b)), b))
            if not cands:
                raise Refused(side, 'no leg on the %s side' % side)
            legs[side] = self.leg(min(cands)[2], side)
        return legs

    def leg(self, foot, side):
        path = self.chain(foot)
        moving = [j for j in path if self.joints[j].get('type') != 'fixed']
        if moving:
            first, last = path.index(moving[0]), path.index(moving[-1])
            for j in path[first:last]:
                if self.joints[j].get('type') == 'fixed':
                    raise Refused(j, 'is a fixed joint inside the %s leg (locked)' % side)
        for j in moving:
            if self.joints[j].get('type') not in ('revolute', 'continuous'):
                raise Refused(j, 'type %s in the %s leg' % (self.joints[j].get('type'), side))
        if len(moving) != 6:
            raise Refused(foot, 'ends the %s leg, whose path has %d joints, not 6 (%s)' % (side, len(moving), ', '.join(moving)))
        for k, j in enumerate(moving):
            el = self.joints[j]
            if el.find('mimic') is not None:
                raise Refused(j, 'is a mimic joint in the %s leg' % side)
            lim = el.find('limit')
            if el.get('type') == 'revolute':
                lo, hi = (float(lim.get('lower', 0)), float(lim.get('upper', 0))) if lim is not None else (0, 0)
                if lo == hi:
                    raise Refused(j, 'lower == upper (%g) in the %s leg (locked)' % (lo, side))
            a = self.world_axis(j, self.zero)
            want = {'x': 0, 'y': 1, 'z': 2}[EXPECTED[k]]
            if abs(a[want]) < 0.99:
                raise Refused(j, '%s joint of the %s leg has world axis %s, not along %s'
                              % (NAMES[k], side, fmt(a), EXPECTED[k]))
            if k == 3 and el.get('type') == 'revolute':
                # The stance bends the knee back: a positive angle about the world's +y.
                bend = BEND if a[want] > 0 else -BEND
                if not lo <= bend <= hi:
                    raise Refused(j, 'limits [%g, %g] exclude the stance bend %g rad (a knee that bends forward)'
                                  % (lo, hi, bend))
        pos = {j: self.zero[self.joints[j].find('child').get('link')][0] for j in moving}
        for k1, k2, what in ((1, 2, 'hip roll and pitch'), (4, 5, 'ankle pitch and roll')):
            j1, j2 = moving[k1], moving[k2]
            a1, a2 = self.world_axis(j1, self.zero), self.world_axis(j2, self.zero)
            n = cross(a1, a2)
            dist = abs(dot(sub(pos[j2], pos[j1]), n)) / norm(n)
            if dist > 1e-3:
                raise Refused(j2, '%s axes do not cross (%.4f m apart)' % (what, dist))
        hip, knee, ankle = pos[moving[2]], pos[moving[3]], pos[moving[4]]
        for a, b, what in ((hip, knee, moving[3]), (knee, ankle, moving[4])):
            d = sub(b, a)
            if abs(d[0]) > 0.03 or abs(d[1]) > 0.005 or d[2] > -0.05:
                raise Refused(what, 'leg not straight and vertical in the zero pose (offset %s)' % fmt(d))
        sole = self.sole(foot, self.zero)
        return {'joints': moving, 'foot': foot, 'hip': hip, 'knee': knee, 'ankle': ankle, 'sole': sole}

    def sole(self, foot, poses):
        best = None
        for l in self.group(foot):
            for c in self.links[l].findall('collision'):
                g = c.find('geometry')[0]
                if g.tag != 'box':
                    continue
                xyz, rot = origin(c, l)
                p, r = poses[l]
                cr = matmul(r, rot)
                if any(abs(abs(x) - 1) > 1e-6 and abs(x) > 1e-6 for row in cr for x in row):
                    raise Refused(l, 'sole box is not axis-aligned')
                size = [float(s) for s in g.get('size').split()]
                half = [sum(abs(cr[i][k]) * size[k] / 2 for k in range(3)) for i in range(3)]
                centre = add(p, apply(r, xyz))
                lo = [centre[i] - half[i] for i in range(3)]
                hi = [centre[i] + half[i] for i in range(3)]
                if best is None or lo[2] < best[0][2]:
                    best = (lo, hi, l)
        if best is None:
            raise Refused(foot, 'foot has no box collision for a sole')
        return best

    def com(self, poses):
        m_tot, acc = 0.0, [0, 0, 0]
        for name, l in self.links.items():
            inert = l.find('inertial')
            if inert is None:
                continue
            m = float(inert.find('mass').get('value'))
            xyz, _ = origin(inert, name)
            p, r = poses[name]
            acc = add(acc, [m * c for c in add(p, apply(r, xyz))])
            m_tot += m
        return m_tot, [c / m_tot for c in acc]

    def stance(self, legs):
        """Knees bent by BEND, shanks and thighs tilted equally: feet flat, trunk upright."""
        q = {}
        for leg in legs.values():
            hp, kn, ap = leg['joints'][2], leg['joints'][3], leg['joints'][4]
            for j, world in ((hp, -BEND / 2), (kn, BEND), (ap, -BEND / 2)):
                q[j] = world / self.world_axis(j, self.zero)[1]
        return q


def fmt(v):
    return '(' + ', '.join('%.4f' % x for x in v) + ')'


def inside_hull(pt, pts):
    pts = sorted(set(pts))
    if len(pts) < 3:
        return False

    def half(seq):
        h = []
        for p in seq:
            while len(h) >= 2 and ((h[-1][0] - h[-2][0]) * (p[1] - h[-2][1]) - (h[-1][1] - h[-2][1]) * (p[0] - h[-2][0])) <= 0:
                h.pop()
            h.append(p)
        return h
    hull = half(pts)[:-1] + half(reversed(pts))[:-1]
    for a, b in zip(hull, hull[1:] + hull[:1]):
        if (b[0] - a[0]) * (pt[1] - a[1]) - (b[1] - a[1]) * (pt[0] - a[0]) < 0:
            return False
    return True


def check(path):
    rob = Robot(path)
    legs = rob.legs()
    for name, l in rob.links.items():
        for c in l.findall('collision'):
            g = c.find('geometry')[0]
            if g.tag not in ('box', 'sphere', 'cylinder', 'capsule'):
                if not (g.tag == 'mesh' and name in rob.group(legs['left']['foot']) + rob.group(legs['right']['foot'])):
                    print('  note: %s has a %s collision (not a supported collision shape)' % (name, g.tag))
    mass, com0 = rob.com(rob.zero)
    q = rob.stance(legs)
    bent = rob.fk(q)
    _, com1 = rob.com(bent)
    corners = []
    for leg in legs.values():
        lo, hi, _ = rob.sole(leg['foot'], bent)
        corners += [(lo[0], lo[1]), (lo[0], hi[1]), (hi[0], lo[1]), (hi[0], hi[1])]
    if not inside_hull((com1[0], com1[1]), corners):
        raise Refused(rob.root, 'centre of mass %s in the knee-bent stance is outside the support polygon x %.3f..%.3f'
                      % (fmt(com1), min(c[0] for c in corners), max(c[0] for c in corners)))
    ground = min(leg['sole'][0][2] for leg in legs.values())
    rep = ['  total mass %.3f kg; %d links, %d joints; root %s' % (mass, len(rob.links), len(rob.joints), rob.root)]
    top = max(p[0][2] for p in rob.zero.values())
    rep.append('  highest link frame %.3f m above the soles' % (top - ground))
    for side, leg in legs.items():
        lo, hi, sl = leg['sole']
        rep.append('  %s leg: %s; foot %s (sole box on %s)' % (side, ' '.join(leg['joints']), leg['foot'], sl))
        rep.append('    hip pitch at %s, %.3f m above the sole; thigh %.3f, shank %.3f, ankle %.3f above the sole'
                   % (fmt(leg['hip']), leg['hip'][2] - ground, norm(sub(leg['knee'], leg['hip'])),
                      norm(sub(leg['ankle'], leg['knee'])), leg['ankle'][2] - lo[2]))
        rep.append('    sole %.3f x %.3f m, x %.3f..%.3f, y %.3f..%.3f' % (hi[0] - lo[0], hi[1] - lo[1], lo[0], hi[0], lo[1], hi[1]))
    rep.append('  CoM zero pose %s, %.3f m above the soles' % (fmt(com0), com0[2] - ground))
    rep.append('  CoM knee-bent stance (%.2f rad) %s; support x %.3f..%.3f, y %.3f..%.3f'
               % (BEND, fmt(com1), min(c[0] for c in corners), max(c[0] for c in corners),
                  min(c[1] for c in corners), max(c[1] for c in corners)))
    return rep


def main(argv):
    expect_refused = '--expect-refused' in argv
    files = [a for a in argv if a != '--expect-refused']
    bad = 0
    for f in files:
        try:
            rep = check(f)
            print('ACCEPTED %s' % f)
            print('\n'.join(rep))
            bad += expect_refused
        except Refused as e:
            print('REFUSED  %s: %s' % (f, e))
            bad += not expect_refused
    return 1 if bad else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
