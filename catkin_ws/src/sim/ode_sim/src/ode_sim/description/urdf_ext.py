"""The <gazebo> and <transmission> parts of a URDF (urdf.py's parser inherits these methods):
per-link and per-joint Gazebo extensions, surfaces, plugins and ros_control transmissions."""
from ode_sim.description.model import Surface, Transmission
from ode_sim.description.sdf_elements import parse_surface
from ode_sim.description.sdf_sensors import parse_plugin

TRUE = ('1', 'true', 'yes')
IGNORED_LINK_EXT = ('dampingFactor', 'maxContacts', 'mu', 'kp_', 'velocity_decay',
                    'enable_wind')


class GazeboExtensions:
    """Mixin of urdf's parser: needs its err(), warn(), ext_float(), ctx and model state."""

    def parse_gazebo(self, root, links, joints, model):
        link_ext, joint_ext = {}, {}
        for g in root.findall('gazebo'):
            ref = (g.get('reference') or '').strip()
            if not ref:
                for c in g:
                    if c.tag == 'plugin':
                        model.plugins.append(parse_plugin(self.ctx, c))
                    elif c.tag == 'static':
                        model.static = (c.text or '').strip().lower() in TRUE
                    elif c.tag == 'self_collide':
                        pass
                    elif isinstance(c.tag, str):
                        self.warn(c, '<gazebo><%s> is ignored' % c.tag)
                continue
            if ref in links:
                link_ext.setdefault(ref, []).append(g)
            elif ref in joints:
                joint_ext.setdefault(ref, []).append(g)
            else:
                self.warn(g, "<gazebo reference='%s'>: no link or joint of that name" % ref)
        return link_ext, joint_ext

    def joint_flag(self, joint_ext, name, tag):
        val = False
        for g in joint_ext.get(name, []):
            for c in g.findall(tag):
                val = (c.text or '').strip().lower() in TRUE
        return val

    def link_extension(self, name, link_ext):
        """Merged <gazebo reference=name> settings of one URDF link."""
        ext = {'sensors': []}
        for g in link_ext.get(name, []):
            for c in g:
                if not isinstance(c.tag, str):
                    continue
                tag = c.tag
                if tag in ('mu1', 'mu2', 'kp', 'kd', 'maxVel', 'minDepth', 'laserRetro'):
                    ext[tag] = self.ext_float(c)
                elif tag == 'fdir1':
                    try:
                        v = tuple(float(x) for x in (c.text or '').split())
                    except ValueError:
                        v = ()
                    if len(v) != 3:
                        raise self.err(c, '<fdir1> must be 3 numbers')
                    ext['fdir1'] = v if any(v) else None
                elif tag == 'selfCollide':
                    ext['selfCollide'] = (c.text or '').strip().lower() in TRUE
                elif tag == 'turnGravityOff':
                    if (c.text or '').strip().lower() in TRUE:
                        ext['gravity'] = False
                elif tag == 'gravity':
                    ext['gravity'] = (c.text or '').strip().lower() in TRUE
                elif tag == 'material':
                    ext['material'] = (c.text or '').strip()
                    ext['material_where'] = self.doc.where(c)
                elif tag == 'sensor':
                    ext['sensors'].append(c)
                elif tag == 'collision':
                    s = c.find('surface')
                    if s is not None:
                        ext['surface_blob'] = s
                elif tag == 'visual':
                    m = c.find('material')
                    if m is not None:
                        d = self.ctx.color(m, 'diffuse', None) or self.ctx.color(m, 'ambient',
                                                                                 None)
                        if d is not None:
                            ext['visual_diffuse'] = d
                        sc = m.find('script')
                        if sc is not None and sc.find('name') is not None and d is None:
                            ext['material'] = (sc.find('name').text or '').strip()
                            ext['material_where'] = self.doc.where(sc)
                elif tag == 'plugin':
                    self.warn(c, "<plugin> inside <gazebo reference='%s'> is ignored: put model "
                                 "plugins in a <gazebo> without reference, sensor plugins in "
                                 "the <sensor>" % name)
                elif tag in IGNORED_LINK_EXT:
                    pass
                else:
                    self.warn(c, "<gazebo reference='%s'><%s> is ignored" % (name, tag))
        return ext

    def surface_for(self, ext, member):
        s = Surface()
        if 'surface_blob' in ext:
            parse_surface(self.ctx, ext['surface_blob'], s)
        for tag, attr in (('mu1', 'mu1'), ('mu2', 'mu2'), ('kp', 'kp'), ('kd', 'kd'),
                          ('maxVel', 'max_vel'), ('minDepth', 'min_depth')):
            if tag in ext:
                setattr(s, attr, ext[tag])
        if 'fdir1' in ext:
            s.fdir1 = ext['fdir1']
        return s

    def parse_transmissions(self, root, model, joints):
        known = {j.name for j in model.joints} | set(joints)
        for t in root.findall('transmission'):
            name = self.attr(t, 'name', 'transmission')
            ttype = (t.findtext('type') or t.get('type') or '').strip()
            if not ttype:
                self.warn(t, "transmission '%s' has no <type>" % name)
            tr = Transmission(name=name, type=ttype)
            for j in t.findall('joint'):
                jn = self.attr(j, 'name', 'transmission joint')
                if jn not in known:
                    self.warn(j, "transmission '%s' names joint '%s', which the robot does not "
                                 "have" % (name, jn))
                ifaces = []
                for hi in j.findall('hardwareInterface'):
                    v = (hi.text or '').strip()
                    if not v:
                        continue
                    if v.startswith('hardware_interface/'):
                        v = v[len('hardware_interface/'):]
                    else:
                        self.warn(hi, "Deprecated syntax, please prepend 'hardware_interface/' "
                                      "to '%s' within the <hardwareInterface> tag in joint '%s'."
                                  % (v, jn))
                    ifaces.append(v)
                if not ifaces:
                    self.warn(j, "transmission '%s': joint '%s' has no <hardwareInterface>"
                              % (name, jn))
                tr.joints[jn] = ifaces
            for a in t.findall('actuator'):
                an = self.attr(a, 'name', 'transmission actuator')
                red = a.find('mechanicalReduction')
                tr.actuators[an] = self.ext_float(red) if red is not None else 1.0
            model.transmissions.append(tr)
