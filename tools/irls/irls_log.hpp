// The batch (IRLS) estimate over a run's log (tools/irls, docs/estimation.md "IRLS over a run"):
// reads DIR/log.csv as mrqp-run writes it with an `estimation:` section, takes for each estimated
// entity the regression rows of every accepted filter update (columns est_E_rowI_NAME and
// est_E_rowI_mu, already whitened by the filter's R: unit noise), stacks them and solves them by
// irlsEstimate (Huber IRLS, the paper's offline method), optionally with the filter's prior as
// pseudo-rows (θ₀ ± σ₀ from the log's first row). Next to it: the online filter's final state θ and
// its deviations (est_E_theta_NAME, est_E_theta_std_NAME of the last row). Offline: allocates,
// throws std::runtime_error with "FILE:LINE: message" on a bad log.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "estimation/irls.hpp"

namespace mrqp::irls {

/// One estimated entity's data from the log.
struct EntityBatch {
  std::string entity;
  std::vector<std::string> names;  ///< the filter's state θ (m, hx, …; JOINT_K, …)
  Eigen::MatrixXd Y;               ///< stacked whitened rows (updates × nv, p columns)
  Eigen::VectorXd mu;
  Eigen::VectorXd prior, prior_std;    ///< θ₀, σ₀ (the log's first row)
  Eigen::VectorXd online, online_std;  ///< the filter's θ and σ at the log's last row
  long updates = 0;                    ///< accepted updates found
};

/// Every entity of the log at `csv_path` that has regression columns.
std::vector<EntityBatch> readBatches(const std::string& csv_path);

struct BatchResult {
  EntityBatch batch;
  estimation::IrlsResult irls;
  Eigen::VectorXd batch_std;  ///< √diag(covariance)
};

/// The IRLS estimate of one entity; `with_prior` adds θ₀ ± σ₀ as p more rows.
BatchResult estimate(const EntityBatch& b, bool with_prior, const estimation::IrlsOptions& options);

/// The results as a JSON object {"ENTITY": {"parameters": {...}, ...}, ...}.
std::string toJson(const std::vector<BatchResult>& results, bool with_prior, double huber_k);

/// One line per parameter: name, batch ± σ, online ± σ, difference in combined σ.
std::string toText(const std::vector<BatchResult>& results);

}  // namespace mrqp::irls
