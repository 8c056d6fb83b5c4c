import sys, xml.etree.ElementTree as ET
src, k, out = sys.argv[1], float(sys.argv[2]), sys.argv[3]
t = ET.parse(src); r = t.getroot()
leg = ('hip', 'thigh', 'shank', 'ankle', 'foot')
moved = 0.0
for link in r.findall('link'):
    n = link.get('name')
    if any(p in n for p in leg) and n != 'trunk':
        m = link.find('inertial/mass'); i = link.find('inertial/inertia')
        old = float(m.get('value')); new = old * k; moved += old - new
        m.set('value', repr(new))
        for a in ('ixx','iyy','izz','ixy','ixz','iyz'):
            if i.get(a) is not None: i.set(a, repr(float(i.get(a)) * k))
for link in r.findall('link'):
    if link.get('name') == 'trunk':
        m = link.find('inertial/mass'); m.set('value', repr(float(m.get('value')) + moved))
t.write(out)
print('moved', moved)
