// The brain panel: a creature's neurons in three columns (sensors, hidden, actuators) and its
// links, drawn on the page's 'brain' canvas, each neuron labelled with what it senses or drives
// ('hinge j3', as the pictures label them).

function functionName(f) { return typeof f === 'string' ? f : Object.keys(f || {})[0] || '?'; }

export function drawBrain(brain, joints) {
  const canvas = document.getElementById('brain');
  const g = canvas.getContext('2d');
  const W = canvas.width, H = canvas.height;
  g.clearRect(0, 0, W, H);
  const neurons = brain ? brain.neurons : [];
  if (!neurons.length) {
    g.fillStyle = '#778'; g.font = '13px system-ui'; g.textAlign = 'center';
    g.fillText('no neurons', W / 2, H / 2);
    return;
  }
  // Columns: sensors, hidden neurons, actuators.
  const column = (n) => n.role.kind === 'sensor' ? 0 : (n.role.kind === 'actuator' ? 2 : 1);
  const columns = [[], [], []];
  neurons.forEach((n, i) => columns[column(n)].push(i));
  const pos = [];
  columns.forEach((ids, c) => {
    ids.forEach((id, k) => {
      pos[id] = [W * (0.1 + 0.33 * c), 16 + (H - 16) * (k + 1) / (ids.length + 1)];
    });
  });
  const r = Math.max(3, Math.min(10, H / (2.5 * Math.max(...columns.map((c) => c.length)))));
  const maxW = Math.max(1e-9, ...brain.links.map((l) => Math.abs(l.weight)));
  for (const l of brain.links) {
    const a = pos[l.from], b = pos[l.to];
    if (!a || !b) continue;
    g.strokeStyle = l.weight >= 0 ? 'rgba(30,30,40,0.75)' : 'rgba(210,30,30,0.8)';
    g.lineWidth = 0.6 + 2.4 * Math.abs(l.weight) / maxW;
    g.beginPath();
    if (l.from === l.to) {
      g.arc(a[0], a[1] - r * 1.6, r * 0.9, 0, 2 * Math.PI);
    } else {
      const mx = (a[0] + b[0]) / 2 + (b[1] - a[1]) * 0.15, my = (a[1] + b[1]) / 2 - (b[0] - a[0]) * 0.15;
      g.moveTo(a[0], a[1]);
      g.quadraticCurveTo(mx, my, b[0], b[1]);
    }
    g.stroke();
    // A dot at the receiving end.
    const t = 0.85;
    const ex = l.from === l.to ? a[0] : (1 - t) * (1 - t) * a[0] + 2 * (1 - t) * t * ((a[0] + b[0]) / 2 + (b[1] - a[1]) * 0.15) + t * t * b[0];
    const ey = l.from === l.to ? a[1] - r * 0.7 : (1 - t) * (1 - t) * a[1] + 2 * (1 - t) * t * ((a[1] + b[1]) / 2 - (b[0] - a[0]) * 0.15) + t * t * b[1];
    g.fillStyle = g.strokeStyle;
    g.beginPath(); g.arc(ex, ey, 2, 0, 2 * Math.PI); g.fill();
  }
  neurons.forEach((n, i) => {
    const [x, y] = pos[i];
    const kind = n.role.kind;
    g.fillStyle = kind === 'sensor' ? '#2a9d4a' : kind === 'actuator' ? '#d33' :
      functionName(n.function) === 'oscillator' ? '#8a3fbf' : '#3f6fd0';
    g.beginPath(); g.arc(x, y, r, 0, 2 * Math.PI); g.fill();
    g.fillStyle = '#222'; g.font = '10px system-ui'; g.textAlign = 'left';
    g.fillText(String(i) + ' ' + neuronLabel(n, joints || []), x + r + 3, y + 3);
  });
  g.fillStyle = '#556'; g.font = '10px system-ui'; g.textAlign = 'center';
  ['sensors', 'hidden', 'actuators'].forEach((t, c) => g.fillText(t, W * (0.1 + 0.33 * c), 10));
}

// A joint's degree of freedom as labels name it: 'hinge j3', or 'universal j2 axis 1' for a
// joint of several axes (as the pictures do).
const DOFS = { rigid: 0, revolute: 1, twist: 1, universal: 2, 'bend-twist': 2, 'twist-bend': 2, spherical: 3 };
function jointLabel(joints, joint, dof) {
  const j = joints[joint];
  if (!j) return 'joint j' + joint;
  const name = { revolute: 'hinge', spherical: 'ball' }[j.kind] || j.kind;
  return name + ' j' + joint + ((DOFS[j.kind] || 0) > 1 ? ' axis ' + dof : '');
}

function neuronLabel(n, joints) {
  if (n.role.kind === 'sensor') {
    const s = n.role.sensor;
    if (s.joint !== undefined) return s.type + ' ' + jointLabel(joints, s.joint, s.dof);
    return s.type + (s.part !== undefined ? ' p' + s.part : '') + (s.slot !== undefined ? ' ' + s.slot : '');
  }
  if (n.role.kind === 'actuator') {
    const a = n.role.actuator;
    return a.joint !== undefined ? jointLabel(joints, a.joint, a.dof) : a.type + (a.slot !== undefined ? ' ' + a.slot : '');
  }
  return functionName(n.function);
}
