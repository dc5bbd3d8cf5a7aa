// The viewer file: the front end on the run embedded in the page.
(function () {
  const D = JSON.parse(document.getElementById("camlink-data").textContent);
  const front = camlinkFront.create(document.getElementById("app"), {
    width: D.view.width, height: D.view.height, plotWidth: D.view.plot_width, plotHeight: D.view.plot_height,
  });
  front.setData(D);
  window.camlinkViewer = {
    rows: front.rows(), frame: front.frame, time: front.time, seek: front.seek, setFrame: front.setFrame,
    stats: front.stats, pixel: front.pixel, channel: front.channel, front: front,
  };
})();
