// The live viewer's page. It polls /api/state twice a second and redraws what changed: the
// global map (an SVG with the map picture, each robot's trajectory and a marker at its pose),
// robots not placed yet, each robot's health and own map, and every pair's newest merge.

#include "live_viewer.hpp"

namespace mrslam::fusion {

const char* viewerPage() {
  return R"html(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>mrslam live view</title>
<style>
  body { font-family: sans-serif; margin: 0; background: #f4f4f4; color: #222; }
  header { background: #2b3a4a; color: #fff; padding: 6px 12px; display: flex; gap: 24px; }
  header h1 { font-size: 18px; margin: 0; }
  main { display: flex; gap: 12px; padding: 12px; align-items: flex-start; }
  #view { flex: 3; background: #808080; min-height: 300px; }
  #global { width: 100%; height: 75vh; display: block; }
  #global image { image-rendering: pixelated; }
  aside { flex: 2; min-width: 360px; }
  table { border-collapse: collapse; width: 100%; background: #fff; margin-bottom: 12px; }
  th, td { border: 1px solid #ccc; padding: 3px 6px; font-size: 13px; text-align: left; }
  .swatch { display: inline-block; width: 12px; height: 12px; border-radius: 6px; }
  .bad { color: #b00; font-weight: bold; }
  .thumbs { display: flex; flex-wrap: wrap; gap: 8px; }
  .thumbs figure { margin: 0; background: #fff; padding: 4px; }
  .thumbs img { max-width: 160px; max-height: 160px; image-rendering: pixelated; display: block; }
  #unplaced { padding: 6px; background: #fff; min-height: 20px; }
  #unplaced .robot-marker { margin-right: 12px; }
  #empty { padding: 40px; color: #fff; }
</style>
</head>
<body>
<header><h1>mrslam live view</h1><span id="summary">waiting for the fusion agent</span>
<span id="connection"></span></header>
<main>
  <section id="view">
    <div id="empty">no global map yet</div>
    <svg id="global" xmlns="http://www.w3.org/2000/svg">
      <image id="global-image" x="0" y="0"></image>
      <g id="trajectories"></g>
      <g id="markers"></g>
    </svg>
    <div id="unplaced"><b>Not placed:</b> <span id="unplaced-list"></span></div>
  </section>
  <aside>
    <h3>Robots</h3>
    <table><thead><tr><th></th><th>robot</th><th>state</th><th>placement</th><th>V</th>
      <th>scans</th><th>last map</th><th>sensors</th></tr></thead>
      <tbody id="robots"></tbody></table>
    <h3>Pairwise merges</h3>
    <table><thead><tr><th>from → to</th><th>method</th><th>accepted</th><th>V</th>
      <th>entropy</th><th>ms</th><th>reason</th></tr></thead>
      <tbody id="pairs"></tbody></table>
    <h3>Robots' own maps</h3>
    <div class="thumbs" id="thumbs"></div>
  </aside>
</main>
<script>
'use strict';
const svgNS = 'http://www.w3.org/2000/svg';
let shownRevision = -1;

function element(tag, attributes, text) {
  const node = tag.startsWith('svg:') ? document.createElementNS(svgNS, tag.slice(4))
                                      : document.createElement(tag);
  for (const [name, value] of Object.entries(attributes || {})) node.setAttribute(name, value);
  if (text !== undefined) node.textContent = text;
  return node;
}

function fixed(value, digits) {
  return value === null || value === undefined ? '–' : Number(value).toFixed(digits);
}

function drawGlobalMap(state) {
  const svg = document.getElementById('global');
  const map = state.map;
  document.getElementById('empty').style.display = map ? 'none' : 'block';
  svg.style.display = map ? 'block' : 'none';
  const trajectories = document.getElementById('trajectories');
  const markers = document.getElementById('markers');
  trajectories.replaceChildren();
  markers.replaceChildren();
  if (!map) return;
  svg.setAttribute('viewBox', `0 0 ${map.width} ${map.height}`);
  const image = document.getElementById('global-image');
  image.setAttribute('width', map.width);
  image.setAttribute('height', map.height);
  image.setAttribute('href', `/api/global.png?revision=${state.revision}`);
  const toPixel = (x, y) => [(x - map.origin[0]) / map.resolution,
                             map.height - (y - map.origin[1]) / map.resolution];
  const radius = Math.max(3, 0.25 / map.resolution);
  for (const robot of state.robots) {
    if (!robot.placed) continue;
    const points = robot.trajectory.map(([x, y]) => toPixel(x, y).join(',')).join(' ');
    trajectories.appendChild(element('svg:polyline', {
      points, fill: 'none', stroke: robot.colour, 'stroke-width': 2,
      'vector-effect': 'non-scaling-stroke', class: 'trajectory', 'data-robot': robot.id}));
    const pose = robot.pose || robot.origin;
    const [px, py] = toPixel(pose.x, pose.y);
    const marker = element('svg:g', {class: 'robot-marker placed', 'data-robot': robot.id,
                                      transform: `translate(${px},${py})`});
    marker.appendChild(element('svg:circle', {r: radius, fill: robot.colour, stroke: '#fff',
                                              'stroke-width': radius / 4}));
    marker.appendChild(element('svg:line', {
      x1: 0, y1: 0, x2: 2 * radius * Math.cos(pose.theta), y2: -2 * radius * Math.sin(pose.theta),
      stroke: robot.colour, 'stroke-width': radius / 2}));
    marker.appendChild(element('svg:text', {x: radius * 1.2, y: -radius * 1.2, fill: robot.colour,
                                            'font-size': radius * 1.8, 'font-weight': 'bold',
                                            stroke: '#fff', 'stroke-width': radius / 5,
                                            'paint-order': 'stroke'},
                               robot.id));
    markers.appendChild(marker);
  }
}

function drawUnplaced(state) {
  const list = document.getElementById('unplaced-list');
  list.replaceChildren();
  for (const robot of state.robots) {
    if (robot.placed) continue;
    const marker = element('span', {class: 'robot-marker unplaced', 'data-robot': robot.id});
    marker.appendChild(element('span', {class: 'swatch', style: `background:${robot.colour}`}));
    marker.appendChild(document.createTextNode(` ${robot.id} (${robot.source})`));
    list.appendChild(marker);
  }
  if (!list.childElementCount) list.textContent = 'none';
}

function sensorsText(health) {
  if (!health) return '–';
  return health.sensors.map(s => `${s.name} ${s.source} ${fixed(s.rate_hz, 1)} Hz` +
                                 (s.errors ? ` (${s.errors} errors)` : '') +
                                 (s.healthy ? '' : ' UNHEALTHY')).join('; ');
}

function drawRobots(state) {
  const rows = document.getElementById('robots');
  rows.replaceChildren();
  for (const robot of state.robots) {
    const row = element('tr', {'data-robot': robot.id});
    const swatch = element('td');
    swatch.appendChild(element('span', {class: 'swatch', style: `background:${robot.colour}`}));
    row.appendChild(swatch);
    row.appendChild(element('td', {}, robot.id));
    const health = robot.health;
    let state_text = health ? health.state : 'no status';
    if (robot.map && robot.map.stale) state_text += ' (silent)';
    if (robot.map && robot.map.final) state_text += ' (final map)';
    const failed = (health && health.state === 'failed') || (robot.map && robot.map.stale);
    row.appendChild(element('td', failed ? {class: 'bad'} : {}, state_text));
    row.appendChild(element('td', {}, robot.placed ? robot.source : `not placed: ${robot.source}`));
    row.appendChild(element('td', {}, fixed(robot.verification, 3)));
    row.appendChild(element('td', {}, health ? health.scans_processed
                                             : (robot.map ? robot.map.scans_inserted : '–')));
    row.appendChild(element('td', {}, robot.map ?
        `#${robot.map.sequence}, ${fixed(robot.map.seconds_since_map, 1)} s ago` : 'none'));
    row.appendChild(element('td', {}, sensorsText(health)));
    rows.appendChild(row);
  }
}

function drawPairs(state) {
  const rows = document.getElementById('pairs');
  rows.replaceChildren();
  for (const pair of state.pairs) {
    const row = element('tr', {class: pair.accepted ? 'accepted' : 'refused'});
    row.appendChild(element('td', {}, `${pair.from} → ${pair.to}`));
    row.appendChild(element('td', {}, pair.method));
    row.appendChild(element('td', pair.accepted ? {} : {class: 'bad'}, pair.accepted ? 'yes' : 'no'));
    row.appendChild(element('td', {}, fixed(pair.verification, 3)));
    row.appendChild(element('td', {}, fixed(pair.entropy, 3)));
    row.appendChild(element('td', {}, fixed(pair.time_ms, 0)));
    row.appendChild(element('td', {}, pair.reason));
    rows.appendChild(row);
  }
}

function drawThumbnails(state) {
  const thumbs = document.getElementById('thumbs');
  thumbs.replaceChildren();
  for (const robot of state.robots) {
    if (!robot.map) continue;
    const figure = element('figure');
    figure.appendChild(element('img', {alt: robot.id, style: `border: 3px solid ${robot.colour}`,
                                       src: `/api/robot/${robot.id}.png?sequence=${robot.map.sequence}`}));
    figure.appendChild(element('figcaption', {}, robot.id));
    thumbs.appendChild(figure);
  }
}

function render(state) {
  drawGlobalMap(state);
  drawUnplaced(state);
  drawRobots(state);
  drawPairs(state);
  drawThumbnails(state);
  const placed = state.robots.filter(r => r.placed).length;
  document.getElementById('summary').textContent =
      `${state.robots.length} robots, ${placed} placed, reference ${state.reference || '–'}, ` +
      `revision ${state.revision}`;
}

async function poll() {
  try {
    const response = await fetch('/api/state', {cache: 'no-store'});
    const state = await response.json();
    document.getElementById('connection').textContent = `updated ${new Date().toLocaleTimeString()}`;
    if (state.revision !== shownRevision) {
      shownRevision = state.revision;
      render(state);
    }
  } catch (error) {
    document.getElementById('connection').textContent = `fusion agent unreachable (${error})`;
  }
  setTimeout(poll, 500);
}
poll();
</script>
</body>
</html>
)html";
}

}  // namespace mrslam::fusion
